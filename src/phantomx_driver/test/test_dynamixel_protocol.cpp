#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "phantomx_driver/ax12_joint.hpp"
#include "phantomx_driver/dynamixel_packet.hpp"
#include "phantomx_driver/phantomx_parameters.hpp"

using namespace phantomx_driver;
using Bytes = std::vector<uint8_t>;

TEST(DynamixelPacket, EncodesTheHandCheckedFrames)
{
  EXPECT_EQ(writePacket(1, kAddrGoalPosition, le16(512)),
            (Bytes{0xFF, 0xFF, 0x01, 0x05, 0x03, 0x1E, 0x00, 0x02, 0xD6}));
  EXPECT_EQ(writePacket(1, kAddrGoalPosition, Bytes{0x00, 0x02, 0x64, 0x00}),
            (Bytes{0xFF, 0xFF, 0x01, 0x07, 0x03, 0x1E, 0x00, 0x02, 0x64, 0x00, 0x70}));
  EXPECT_EQ(writePacket(1, kAddrGoalPosition, Bytes{0x00, 0x02, 0x00, 0x02}),
            (Bytes{0xFF, 0xFF, 0x01, 0x07, 0x03, 0x1E, 0x00, 0x02, 0x00, 0x02, 0xD2}));  // dfrobot's example
  // READ 2 bytes of present position from ID 1: ~(1+4+2+36+2) = ~45 = 0xD2.
  EXPECT_EQ(readPacket(1, kAddrPresentPosition, 2), (Bytes{0xFF, 0xFF, 0x01, 0x04, 0x02, 0x24, 0x02, 0xD2}));
  EXPECT_EQ(pingPacket(1), (Bytes{0xFF, 0xFF, 0x01, 0x02, 0x01, 0xFB}));
}

TEST(DynamixelPacket, SyncWriteHasTheBroadcastLayout)
{
  const Bytes p = syncWritePacket(kAddrGoalPosition, {{1, le16(512)}, {2, le16(0x3FF)}});
  // FF FF FE LEN 83 1E 02 | 01 00 02 | 02 FF 03 | CHK, LEN = (L+1)·n + 4 = 10
  ASSERT_EQ(p.size(), 14u);
  EXPECT_EQ(p[2], 0xFE);
  EXPECT_EQ(p[3], 10);
  EXPECT_EQ(p[4], 0x83);
  EXPECT_EQ((Bytes(p.begin() + 5, p.end() - 1)), (Bytes{0x1E, 0x02, 0x01, 0x00, 0x02, 0x02, 0xFF, 0x03}));
  unsigned sum = 0;
  for (size_t i = 2; i + 1 < p.size(); ++i)
    sum += p[i];
  EXPECT_EQ(p.back(), static_cast<uint8_t>(~sum));
  EXPECT_THROW(syncWritePacket(30, {{1, le16(1)}, {2, Bytes{1}}}), std::invalid_argument);
}

TEST(DynamixelPacketParser, TakesStatusPacketsAndRejectsEveryCorruptedByte)
{
  const Bytes status{0xFF, 0xFF, 0x01, 0x04, 0x20, 0x00, 0x02, 0xD8};  // ID 1, overload, position 512
  ASSERT_EQ(dynamixelChecksum(1, 4, 0x20, {0x00, 0x02}), 0xD8);
  for (size_t i = 2; i < status.size(); ++i)
  {
    if (i == 3)
      continue;  // a corrupted length is a wait for more bytes, covered below
    Bytes bad = status;
    bad[i] ^= 0x04;
    Bytes stream = bad;
    std::copy(status.begin(), status.end(), std::back_inserter(stream));  // insert(): GCC 12 false -Warray-bounds
    DynamixelPacketParser parser;
    const auto got = parser.feed(stream);
    ASSERT_EQ(got.size(), 1u) << "byte " << i;
    EXPECT_EQ(got[0].id, 1);
    EXPECT_EQ(got[0].code, kErrorOverload);
    EXPECT_EQ(got[0].params, (Bytes{0x00, 0x02}));
    EXPECT_GE(parser.rejected(), 1u);
  }
  DynamixelPacketParser parser;
  Bytes stream{0xFF, 0xFF, 0xFF};  // a run of 0xFF before the header
  std::copy(status.begin() + 2, status.end(), std::back_inserter(stream));
  EXPECT_EQ(parser.feed(stream).size(), 1u);
}

TEST(Ax12Joint, RadiansMapOntoTicksAroundTheCentre)
{
  Ax12Joint j;
  j.lower = -3.0;  // wider than the servo's ±2.62 rad
  j.upper = 3.0;
  EXPECT_EQ(j.goalTicks(0.0), 512);
  EXPECT_NEAR(Ax12Joint::kRadPerTick, 0.0051183, 1e-7);  // 300°/1023
  EXPECT_EQ(j.goalTicks(100 * Ax12Joint::kRadPerTick), 612);
  EXPECT_NEAR(j.radians(612), 100 * Ax12Joint::kRadPerTick, 1e-12);
  EXPECT_EQ(j.goalTicks(10.0), 1023) << "the 0-1023 range caps even wide limits";
  EXPECT_EQ(j.goalTicks(-10.0), 0);
  EXPECT_EQ(j.goalTicks(NAN), -1);
  j.direction = -1;
  j.offset = 0.1;
  for (double rad : {-0.7, 0.0, 0.3, 1.2})
    EXPECT_NEAR(j.radians(j.goalTicks(rad)), rad, 0.5 * Ax12Joint::kRadPerTick);
}

TEST(Ax12Joint, NeverAGoalBeyondTheLimits)
{
  Ax12Joint j;
  j.lower = -0.7854;
  j.upper = 0.7854;
  for (int direction : {1, -1})
  {
    j.direction = direction;
    for (double rad = -4.0; rad <= 4.0; rad += 0.01)
    {
      // Not even the half tick the nearest tick would give at the limit (pan's ±1.5708 was sent as ±1.5713).
      const double reached = j.radians(j.goalTicks(rad));
      EXPECT_GE(reached, j.lower) << rad << " direction " << direction;
      EXPECT_LE(reached, j.upper) << rad << " direction " << direction;
      EXPECT_LE(std::abs(reached - std::clamp(rad, j.lower, j.upper)), Ax12Joint::kRadPerTick + 1e-12);
    }
  }
  j.direction = 1;
  j.lower = -1.5708;
  j.upper = 1.5708;
  EXPECT_LE(j.radians(j.goalTicks(1.5708)), 1.5708);
  EXPECT_GE(j.radians(j.goalTicks(-1.5708)), -1.5708);
}

TEST(Ax12Joint, SpeedConversions)
{
  EXPECT_EQ(movingSpeedTicks(3.0), 258);  // 28.65 rpm / 0.111
  EXPECT_EQ(movingSpeedTicks(0.0), 1) << "never 0 (= uncontrolled maximum)";
  EXPECT_EQ(movingSpeedTicks(100.0), 1023);
  EXPECT_NEAR(presentSpeedRadPerS(100), 100 * 0.111 * 2 * M_PI / 60, 1e-12);
  EXPECT_NEAR(presentSpeedRadPerS(100 | 0x400), -100 * 0.111 * 2 * M_PI / 60, 1e-12);
}

TEST(PhantomXParameters, DefaultsValidateAndEachBadFieldIsNamed)
{
  EXPECT_NO_THROW(PhantomXParameters{}.validate());
  auto expectNamed = [](PhantomXParameters p, const std::string& field) {
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
  PhantomXParameters p;
  p.baud = 9600;
  expectNamed(p, "baud");
  p = {};
  p.tilt_id = 1;
  expectNamed(p, "tilt_id");
  p = {};
  p.pan_id = 254;
  expectNamed(p, "pan_id");
  p = {};
  p.pan_direction = 0;
  expectNamed(p, "pan_direction");
  p = {};
  p.tilt_upper = 3.0;
  expectNamed(p, "tilt_upper");
  p = {};
  p.max_speed = 7.0;
  expectNamed(p, "max_speed");
  p = {};
  p.poll_rate = 10.0;
  expectNamed(p, "poll_rate");
  p = {};
  p.response_timeout = 0.0;
  expectNamed(p, "response_timeout");
  p = {};
  p.lost_after = 0;
  expectNamed(p, "lost_after");
  p = {};
  p.retry_period = NAN;
  expectNamed(p, "retry_period");
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
