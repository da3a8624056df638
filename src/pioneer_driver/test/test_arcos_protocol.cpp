#include <gtest/gtest.h>

#include <cmath>

#include "pioneer_driver/arcos_packet.hpp"
#include "pioneer_driver/pioneer_odometry.hpp"
#include "pioneer_driver/pioneer_parameters.hpp"
#include "pioneer_driver/standard_sip.hpp"

using namespace pioneer_driver;
using Bytes = std::vector<uint8_t>;

TEST(ArcosPacket, EncodesTheHandCheckedFrames)
{
  EXPECT_EQ(arcosCommand(kSync0), (Bytes{0xFA, 0xFB, 0x03, 0x00, 0x00, 0x00}));
  EXPECT_EQ(arcosCommand(kOpen), (Bytes{0xFA, 0xFB, 0x03, 0x01, 0x00, 0x01}));
  EXPECT_EQ(arcosCommand(kEnable, 1), (Bytes{0xFA, 0xFB, 0x06, 0x04, 0x3B, 0x01, 0x00, 0x05, 0x3B}));
  // VEL −300 mm/s: negative type, |v| = 0x012C; checksum 0x0B1B + 0x2C01 = 0x371C.
  EXPECT_EQ(arcosCommand(kVel, -300), (Bytes{0xFA, 0xFB, 0x06, 0x0B, 0x1B, 0x2C, 0x01, 0x37, 0x1C}));
}

TEST(ArcosPacket, ChecksumOfAnOddCountXorsTheLastByte)
{
  // 0x0102 + 0x0304 = 0x0406, then ^ 0x05 = 0x0403.
  EXPECT_EQ(arcosChecksum(Bytes{1, 2, 3, 4, 5}), 0x0403);
  EXPECT_EQ(arcosChecksum(Bytes{0xFF, 0xFF, 0x00, 0x02}), 0x0001) << "the sum wraps modulo 2^16";
}

TEST(ArcosPacket, ArgumentsBeyondSixteenBitsAreClamped)
{
  EXPECT_EQ(arcosCommand(kVel, 100000), arcosCommand(kVel, 32767));
  EXPECT_EQ(arcosCommand(kVel, -100000), arcosCommand(kVel, -32767));
  EXPECT_THROW(encodeArcosPacket({}), std::invalid_argument);
  EXPECT_THROW(encodeArcosPacket(Bytes(199, 0)), std::invalid_argument);
}

TEST(ArcosPacketParser, SplitsAStreamFedByteByByte)
{
  Bytes stream = arcosCommand(kSync0);
  const Bytes enable = arcosCommand(kEnable, 1);
  stream.insert(stream.end(), enable.begin(), enable.end());
  ArcosPacketParser parser;
  std::vector<Bytes> got;
  for (uint8_t b : stream)
    for (auto& p : parser.feed(&b, 1))
      got.push_back(p);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0], Bytes{0});
  EXPECT_EQ(got[1], (Bytes{0x04, 0x3B, 0x01, 0x00}));
  EXPECT_EQ(parser.rejected(), 0u);
}

TEST(ArcosPacketParser, RejectsEveryCorruptedByteAndKeepsTheNextPacket)
{
  const Bytes good = arcosCommand(kEnable, 1);
  // Corrupt each data and checksum byte in turn (not the header: that is a resync, not a packet).
  for (size_t i = 3; i < good.size(); ++i)
  {
    Bytes bad = good;
    bad[i] ^= 0x10;
    Bytes stream = bad;
    stream.insert(stream.end(), good.begin(), good.end());
    ArcosPacketParser parser;
    const auto packets = parser.feed(stream);
    ASSERT_EQ(packets.size(), 1u) << "byte " << i;
    EXPECT_EQ(packets[0], (Bytes{0x04, 0x3B, 0x01, 0x00})) << "byte " << i;
    EXPECT_GE(parser.rejected(), 1u) << "byte " << i;
  }
}

TEST(ArcosPacketParser, RefusesTheFramesP2osAccepts)
{
  // p2os compares chk == (hi << 8) | lo, i.e. (chk == hi<<8) | lo: any nonzero low byte passes.
  Bytes frame = arcosCommand(kEnable, 1);
  frame[7] = 0x00;  // checksum 0x003B instead of 0x053B
  ArcosPacketParser parser;
  EXPECT_TRUE(parser.feed(frame).empty());
  EXPECT_EQ(parser.rejected(), 1u);
}

TEST(ArcosPacketParser, SkipsNoiseAndImpossibleCounts)
{
  Bytes stream{0x00, 0x13, 0xFA, 0xFB, 0xFF, 0x42, 0xFA};  // noise, a count of 255, a lone header byte
  const Bytes sync = arcosCommand(kSync1);
  stream.insert(stream.end(), sync.begin(), sync.end());
  ArcosPacketParser parser;
  const auto packets = parser.feed(stream);
  ASSERT_EQ(packets.size(), 1u);
  EXPECT_EQ(packets[0], Bytes{1});
}

TEST(StandardSip, RoundTripsEveryField)
{
  StandardSip s;
  s.moving = true;
  s.xpos = 32000;
  s.ypos = 17;
  s.thpos = -1024;
  s.left_velocity = -250;
  s.right_velocity = 300;
  s.battery = 124;
  s.stall_bumpers = 0x0101 | (0x05 << 1) | (0x03 << 9);
  s.flags = 1;
  s.sonars = {{3, 1500}, {7, 5000}};
  const StandardSip p = parseStandardSip(encodeStandardSip(s));
  EXPECT_TRUE(p.moving);
  EXPECT_EQ(p.xpos, 32000);
  EXPECT_EQ(p.ypos, 17);
  EXPECT_EQ(p.thpos, -1024);
  EXPECT_EQ(p.left_velocity, -250);
  EXPECT_EQ(p.right_velocity, 300);
  EXPECT_NEAR(p.batteryVolts(), 12.4, 1e-9);
  EXPECT_TRUE(p.leftStall());
  EXPECT_TRUE(p.rightStall());
  EXPECT_EQ(p.frontBumpers(), 0x05);
  EXPECT_EQ(p.rearBumpers(), 0x03);
  EXPECT_TRUE(p.motorsEnabled());
  ASSERT_EQ(p.sonars.size(), 2u);
  EXPECT_EQ(p.sonars[1].second, 5000);
}

TEST(StandardSip, ShortOrForeignPacketsThrow)
{
  EXPECT_THROW(parseStandardSip(Bytes{0x32, 1, 2}), std::invalid_argument);
  EXPECT_THROW(parseStandardSip(Bytes(30, 0x20)), std::invalid_argument);
  Bytes d = encodeStandardSip(StandardSip{});
  d[19] = 50;  // 50 sonar readings announced, none there
  EXPECT_THROW(parseStandardSip(d), std::invalid_argument);
}

TEST(PioneerOdometry, FifteenBitPositionsWrapAround)
{
  EXPECT_EQ(wrappedDelta15(32760, 5), 13);
  EXPECT_EQ(wrappedDelta15(5, 32760), -13);
  EXPECT_EQ(wrappedDelta15(100, 300), 200);
  PioneerOdometry odom;
  double t = 0.0;  // SIPs every 100 ms
  StandardSip s;
  s.xpos = 32000;
  odom.update(s, t += 0.1);
  for (int step = 0; step < 20; ++step)  // 20 × 100 mm across the wrap at 32768
  {
    s.xpos = static_cast<uint16_t>((s.xpos + 100) & 0x7FFF);
    odom.update(s, t += 0.1);
  }
  EXPECT_NEAR(odom.x(), 2.0, 1e-9);
  EXPECT_NEAR(odom.y(), 0.0, 1e-9);
}

TEST(PioneerOdometry, PoseIsRelativeToTheFirstSipAndVelocitiesFollowTheWheels)
{
  PioneerOdometry odom;
  double t = 0.0;  // SIPs every 100 ms
  StandardSip s;
  s.thpos = 1024;  // the controller starts facing +y (π/2)
  s.xpos = 1000;
  s.ypos = 1000;
  odom.update(s, t += 0.1);
  s.ypos = 1500;  // 0.5 m ahead in the controller's frame
  s.left_velocity = 100;
  s.right_velocity = 300;
  odom.update(s, t += 0.1);
  // 1024 units are 1.570816 rad, not exactly π/2: 10 µm of sideways error over 0.5 m.
  EXPECT_NEAR(odom.x(), 0.5, 1e-6);
  EXPECT_NEAR(odom.y(), 0.0, 2e-5);
  EXPECT_NEAR(odom.yaw(), 0.0, 1e-9);
  EXPECT_NEAR(odom.linearVelocity(), 0.2, 1e-9);
  EXPECT_NEAR(odom.angularVelocity(), 100 * 0.0056, 1e-9);
  s.thpos = 1024 + 2048 + 10;  // half a turn on, 1 s later: wraps into (−π, π]
  ASSERT_TRUE(odom.update(s, t += 1.0));
  EXPECT_NEAR(odom.yaw(), normalizeAngle((2048 + 10) * 0.001534), 1e-9);
}

TEST(PioneerOdometry, AnImplausibleSipIsRefusedAndTheNextGoodOneContinues)
{
  PioneerOdometry odom;
  double t = 0.0;  // SIPs every 100 ms
  StandardSip s;
  s.xpos = 1000;
  ASSERT_TRUE(odom.update(s, t += 0.1));
  s.xpos = 1100;
  ASSERT_TRUE(odom.update(s, t += 0.1));
  StandardSip jump = s;
  jump.xpos = 13100;  // 12 m in one SIP, checksum fine
  EXPECT_FALSE(odom.update(jump, t += 0.1));
  StandardSip fast = s;
  fast.left_velocity = fast.right_velocity = 32767;  // 32.8 m/s
  EXPECT_FALSE(odom.update(fast, t += 0.1));
  EXPECT_NEAR(odom.x(), 0.1, 1e-9) << "the refused SIPs moved nothing";
  EXPECT_NEAR(odom.linearVelocity(), 0.0, 1e-9);
  s.xpos = 1200;
  EXPECT_TRUE(odom.update(s, t += 0.1));
  EXPECT_NEAR(odom.x(), 0.2, 1e-9);
  EXPECT_EQ(odom.implausible(), 2u);
}

TEST(PioneerOdometry, CountersThatReallyJumpedAreFollowedAfterThreeSipsWithoutAPoseJump)
{
  PioneerOdometry odom;
  double t = 0.0;  // SIPs every 100 ms
  StandardSip s;
  s.xpos = 1000;
  odom.update(s, t += 0.1);
  s.xpos = 1500;
  odom.update(s, t += 0.1);  // 0.5 m
  s.xpos = 20000;            // the controller's counters restarted elsewhere
  EXPECT_FALSE(odom.update(s, t += 0.1));
  s.xpos = 20010;
  EXPECT_FALSE(odom.update(s, t += 0.1));
  s.xpos = 20020;
  EXPECT_TRUE(odom.update(s, t += 0.1)) << "the third in a row is the new origin";
  EXPECT_NEAR(odom.x(), 0.5, 1e-9);
  s.xpos = 20120;
  EXPECT_TRUE(odom.update(s, t += 0.1));
  EXPECT_NEAR(odom.x(), 0.6, 1e-9);
}

TEST(PioneerOdometry, AfterAReconnectionThePoseGoesOnFromWhereItWas)
{
  PioneerOdometry odom;
  double t = 0.0;  // SIPs every 100 ms
  StandardSip s;
  s.xpos = 1000;
  odom.update(s, t += 0.1);
  for (int i = 0; i < 10; ++i)
  {
    s.xpos = static_cast<uint16_t>(s.xpos + 100);
    odom.update(s, t += 0.1);
  }
  ASSERT_NEAR(odom.x(), 1.0, 1e-9);
  odom.restartCounters();
  StandardSip n;  // the new session's counters start at 0, its heading at +y
  n.thpos = 1024;
  odom.update(n, t += 0.1);
  EXPECT_NEAR(odom.x(), 1.0, 1e-9) << "no jump back to the origin";
  EXPECT_NEAR(odom.yaw(), 0.0, 1e-9);
  n.ypos = 300;  // 0.3 m ahead in the new counters' frame
  odom.update(n, t += 0.1);
  EXPECT_NEAR(odom.x(), 1.3, 1e-4);
  EXPECT_NEAR(odom.y(), 0.0, 1e-4);
}

TEST(PioneerOdometry, FastTurnsAndGapsInTheSipsAtSpeedAreMotionNotJumps)
{
  PioneerOdometry odom;
  double t = 0.0;
  StandardSip s;
  s.xpos = 1000;
  ASSERT_TRUE(odom.update(s, t));
  // 2.2 m/s and 500 deg/s at once: wheels at 2.2 -+ 1.56 m/s, within the P3-DX's reach.
  s.left_velocity = 640;
  s.right_velocity = 3760;
  s.xpos = 1220;
  s.thpos = 85;  // 0.13 rad in 100 ms
  EXPECT_TRUE(odom.update(s, t += 0.1));
  // No SIP for 0.4 s at 2.2 m/s (a dropped stretch): 0.88 m in one step is motion, not a jump.
  s.left_velocity = s.right_velocity = 2200;
  s.xpos = 2100;
  EXPECT_TRUE(odom.update(s, t += 0.4));
  EXPECT_NEAR(odom.linearVelocity(), 2.2, 1e-9);
  EXPECT_EQ(odom.implausible(), 0u);
}

TEST(PioneerOdometry, AHeadingJumpWithAGoodChecksumIsRefused)
{
  PioneerOdometry odom;
  double t = 0.0;
  StandardSip s;
  s.thpos = 100;
  ASSERT_TRUE(odom.update(s, t));
  const double yaw = odom.yaw();
  s.thpos = 100 + 1024;  // a quarter turn in 100 ms: 15.7 rad/s, beyond RVEL's 500 deg/s
  EXPECT_FALSE(odom.update(s, t += 0.1));
  EXPECT_NEAR(odom.yaw(), yaw, 1e-12);
  s.thpos = 110;
  EXPECT_TRUE(odom.update(s, t += 0.1));
}

TEST(ArcosVelocity, TwistIsConvertedAndClampedToTheCaps)
{
  PioneerParameters p;  // 0.5 m/s, 1.745 rad/s (99.98°/s → 99)
  auto a = toArcosVelocity(0.3, 0.5, p);
  EXPECT_EQ(a.vel_mm_s, 300);
  EXPECT_EQ(a.rvel_deg_s, 29);  // 28.65° rounded
  a = toArcosVelocity(5.0, -10.0, p);
  EXPECT_EQ(a.vel_mm_s, 500);
  EXPECT_EQ(a.rvel_deg_s, -99);
  a = toArcosVelocity(NAN, 0.2, p);
  EXPECT_EQ(a, ArcosVelocity{});
  a = toArcosVelocity(0.2, INFINITY, p);
  EXPECT_EQ(a, ArcosVelocity{});
}

TEST(PioneerParameters, DefaultsValidateAndEachBadFieldIsNamed)
{
  EXPECT_NO_THROW(PioneerParameters{}.validate());
  auto expectNamed = [](PioneerParameters p, const std::string& field) {
    try
    {
      p.validate();
      ADD_FAILURE() << field << " accepted";
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  PioneerParameters p;
  p.baud = 4800;
  expectNamed(p, "baud");
  p = {};
  p.max_linear_speed = 3.0;
  expectNamed(p, "max_linear_speed");
  p = {};
  p.max_angular_speed = 0.0;
  expectNamed(p, "max_angular_speed");
  p = {};
  p.cmd_vel_timeout = 5.0;
  expectNamed(p, "cmd_vel_timeout");
  p = {};
  p.pulse_period = 2.0;
  expectNamed(p, "pulse_period");
  p = {};
  p.sip_timeout = 0.1;
  expectNamed(p, "sip_timeout");
  p = {};
  p.reconnect_period = 0.0;
  expectNamed(p, "reconnect_period");
  p = {};
  p.sync_timeout = NAN;
  expectNamed(p, "sync_timeout");
  p = {};
  p.diff_conv_factor = -1;
  expectNamed(p, "diff_conv_factor");
  p = {};
  p.port = "";
  expectNamed(p, "port");
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
