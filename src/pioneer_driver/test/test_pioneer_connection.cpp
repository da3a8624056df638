// The real driver state machine against the ARCOS emulator over a pseudo-terminal (no robot needed).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cmath>
#include <atomic>
#include <functional>
#include <thread>

#include "pioneer_driver/arcos_emulator.hpp"
#include "pioneer_driver/pioneer_connection.hpp"

using namespace pioneer_driver;

namespace
{
double now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Spins the connection until `done` holds or `seconds` pass; calls `command` before each step.
bool spinUntil(PioneerConnection& c, PioneerOdometry* odom, const std::function<bool()>& done, double seconds,
               const std::function<void(double)>& command = nullptr)
{
  const double end = now() + seconds;
  while (now() < end)
  {
    if (command)
      command(now());
    for (const auto& sip : c.spinOnce(now(), 0.02))
      if (odom)
        odom->update(sip, now());
    if (done())
      return true;
  }
  return done();
}

PioneerParameters parametersFor(const ArcosEmulator& emulator)
{
  PioneerParameters p;
  p.port = emulator.port();
  p.baud = 115200;
  p.reconnect_period = 0.2;
  return p;
}
}  // namespace

TEST(PioneerConnection, HandshakesOpensAndEnablesTheMotors)
{
  ArcosEmulator robot;
  PioneerConnection c(parametersFor(robot));
  ASSERT_TRUE(spinUntil(
      c, nullptr, [&] { return c.status().connected && robot.motorsEnabled(); }, 3.0))
      << c.status().last_error;
  EXPECT_EQ(c.status().robot_name, "BioVisionEmulator");
  EXPECT_EQ(c.status().robot_class, "Pioneer");
  EXPECT_EQ(c.status().robot_subclass, "p3dx-sh");
  EXPECT_TRUE(robot.sessionOpen());
  EXPECT_TRUE(spinUntil(
      c, nullptr, [&] { return c.status().sips >= 5; }, 2.0))
      << "SIPs every 100 ms";
}

TEST(PioneerConnection, CommandsArriveClampedAndOdometryFollowsTheRobot)
{
  ArcosEmulator robot;
  PioneerParameters p = parametersFor(robot);
  p.max_linear_speed = 0.4;
  PioneerConnection c(p);
  PioneerOdometry odom(p);
  ASSERT_TRUE(spinUntil(
      c, &odom, [&] { return c.status().connected; }, 3.0))
      << c.status().last_error;
  auto drive = [&](double t) { c.setCommand(1.5, 0.3, t); };  // above the 0.4 m/s cap
  ASSERT_TRUE(spinUntil(
      c, &odom, [&] { return robot.setpoint().vel_mm_s != 0; }, 2.0, drive));
  EXPECT_EQ(robot.setpoint().vel_mm_s, 400);
  EXPECT_EQ(robot.setpoint().rvel_deg_s, 17);  // 0.3 rad/s = 17.2°/s
  spinUntil(
      c, &odom, [] { return false; }, 1.5, drive);
  EXPECT_LE(robot.maxAbsVel(), 400) << "never beyond the cap";
  EXPECT_NEAR(odom.linearVelocity(), 0.4, 0.01);
  EXPECT_NEAR(odom.angularVelocity(), 17 * M_PI / 180.0, 0.01);
  // Stopped, the odometry from the SIPs equals the emulator's true pose (to the mm rounding of XPOS/YPOS
  // and the 4096-step heading); moving, it lags by up to a SIP period, which a loaded machine stretches.
  c.setCommand(0.0, 0.0, now());
  ASSERT_TRUE(spinUntil(
      c, &odom, [&] { return robot.setpoint() == ArcosVelocity{}; }, 1.0));
  spinUntil(
      c, &odom, [] { return false; }, 0.4);
  EXPECT_GT(odom.x(), 0.3);
  EXPECT_NEAR(odom.x(), robot.x(), 0.005);
  EXPECT_NEAR(odom.y(), robot.y(), 0.005);
  EXPECT_NEAR(odom.yaw(), robot.yaw(), 0.003);
}

TEST(PioneerConnection, TheWatchdogStopsTheBaseWithoutCmdVelAndTheResentSetpointKeepsTheSessionAlive)
{
  ArcosEmulator robot;
  PioneerConnection c(parametersFor(robot));
  ASSERT_TRUE(spinUntil(
      c, nullptr, [&] { return c.status().connected; }, 3.0))
      << c.status().last_error;
  const double last_command = now();
  c.setCommand(0.2, 0.0, last_command);
  ASSERT_TRUE(spinUntil(
      c, nullptr, [&] { return robot.setpoint().vel_mm_s == 200; }, 0.4));
  ASSERT_TRUE(spinUntil(
      c, nullptr, [&] { return robot.setpoint().vel_mm_s == 0; }, 2.0));
  const double stopped_after = now() - last_command;
  std::printf("[ MEASURED ] stopped %.3f s after the last command\n", stopped_after);
  EXPECT_GT(stopped_after, 0.5);
  EXPECT_LT(stopped_after, 0.8) << "the driver's 0.5 s time-out, not the robot's 2 s watchdog";
  EXPECT_TRUE(c.status().watchdog_stopped);
  const unsigned long vels = robot.commandCount(kVel);
  spinUntil(
      c, nullptr, [] { return false; }, 2.5);
  EXPECT_GE(robot.commandCount(kVel), vels + 2) << "the zero setpoint again at 1 Hz while idle (the keep-alive)";
  EXPECT_TRUE(c.status().connected);
  EXPECT_TRUE(robot.sessionOpen());
}

TEST(PioneerConnection, ALostStopIsRepeatedWithinThePulsePeriod)
{
  ArcosEmulator robot;
  PioneerParameters p = parametersFor(robot);
  p.pulse_period = 0.3;
  PioneerConnection c(p);
  ASSERT_TRUE(spinUntil(
      c, nullptr, [&] { return c.status().connected; }, 3.0))
      << c.status().last_error;
  auto drive = [&](double t) { c.setCommand(0.3, 0.0, t); };
  ASSERT_TRUE(spinUntil(
      c, nullptr, [&] { return robot.setpoint().vel_mm_s == 300; }, 1.0, drive));
  robot.dropNext(kVel, 1);  // the stop's VEL 0 is lost on the line
  const double stop = now();
  c.setCommand(0.0, 0.0, stop);
  spinUntil(
      c, nullptr, [] { return false; }, 0.1);
  EXPECT_EQ(robot.setpoint().vel_mm_s, 300) << "the stop was lost";
  ASSERT_TRUE(spinUntil(
      c, nullptr, [&] { return robot.setpoint().vel_mm_s == 0; }, 1.5))
      << "never repeated: the base drives on";
  const double stopped_after = now() - stop;
  std::printf("[ MEASURED ] a lost stop repeated and applied %.3f s after it was lost\n", stopped_after);
  EXPECT_LT(stopped_after, 0.8) << "within pulse_period (0.3 s), not the robot's 2 s watchdog";
}

TEST(PioneerConnection, CorruptedSipsAreRejectedAndTheSessionSurvives)
{
  ArcosEmulator robot;
  PioneerConnection c(parametersFor(robot));
  ASSERT_TRUE(spinUntil(
      c, nullptr, [&] { return c.status().connected && c.status().sips > 2; }, 3.0));
  const unsigned long sips = c.status().sips;
  robot.corruptNextSips(5);
  robot.injectBytes({0xFA, 0xFB, 0x20, 0x32, 0x01, 0x02});  // a truncated header-looking fragment
  ASSERT_TRUE(spinUntil(
      c, nullptr, [&] { return c.status().rejected_packets >= 5; }, 2.0))
      << c.status().rejected_packets;
  spinUntil(
      c, nullptr, [] { return false; }, 0.5);
  EXPECT_TRUE(c.status().connected);
  EXPECT_GT(c.status().sips, sips) << "good SIPs after the bad ones are still taken";
  EXPECT_EQ(robot.badChecksums(), 0u) << "the driver's own packets are correct";
}

TEST(PioneerConnection, APulledCableIsReportedAndReconnected)
{
  const std::string link = "/tmp/biovision_pioneer_gtest_" + std::to_string(::getpid());
  ArcosEmulator robot(link);
  PioneerConnection c(parametersFor(robot));
  ASSERT_TRUE(spinUntil(
      c, nullptr, [&] { return c.status().connected; }, 3.0))
      << c.status().last_error;
  c.setCommand(0.3, 0.0, now());
  spinUntil(
      c, nullptr, [] { return false; }, 0.2);
  robot.pullCable();
  ASSERT_TRUE(spinUntil(
      c, nullptr, [&] { return !c.status().connected; }, 2.0));
  EXPECT_EQ(c.status().losses, 1u);
  EXPECT_FALSE(c.status().last_error.empty());
  EXPECT_EQ(c.status().commanded, ArcosVelocity{});
  spinUntil(
      c, nullptr, [] { return false; }, 0.5);  // retries against a missing device: errors, no crash
  EXPECT_FALSE(c.status().connected);
  EXPECT_NE(c.status().last_error.find("connect"), std::string::npos) << c.status().last_error;
  robot.plugIn();  // the controller still has its session open: the driver must CLOSE and resync
  ASSERT_TRUE(spinUntil(
      c, nullptr, [&] { return c.status().connected && c.status().connects == 2; }, 5.0))
      << c.status().last_error;
  EXPECT_TRUE(robot.motorsEnabled());
  EXPECT_EQ(c.status().commanded, ArcosVelocity{}) << "a stale command is not resumed after reconnecting";
}

TEST(PioneerConnection, ASilentRobotIsALostLink)
{
  ArcosEmulator robot("", 100.0);  // one SIP at OPEN, then silent: the robot-to-PC direction is dead
  PioneerParameters p = parametersFor(robot);
  p.sip_timeout = 0.5;
  p.reconnect_period = 5.0;  // no handshake in the window below
  PioneerConnection c(p);
  ASSERT_TRUE(spinUntil(
      c, nullptr, [&] { return c.status().connects >= 1; }, 3.0))
      << c.status().last_error;
  auto drive = [&](double t) { c.setCommand(0.3, 0.0, t); };
  ASSERT_TRUE(spinUntil(
      c, nullptr, [&] { return robot.setpoint().vel_mm_s == 300; }, 1.0, drive));
  ASSERT_TRUE(spinUntil(
      c, nullptr, [&] { return c.status().losses >= 1; }, 2.0, drive));
  EXPECT_NE(c.status().last_error.find("no valid SIP"), std::string::npos) << c.status().last_error;
  // Stopped and closed by the driver at once, not 2 s later by the robot's watchdog (which the
  // reconnection's SYNC0s would feed as PULSEs).
  // (Its watchdog would zero the setpoint 2 s after the last command, but never send CLOSE.)
  EXPECT_TRUE(spinUntil(
      c, nullptr,
      [&] { return robot.setpoint() == ArcosVelocity{} && robot.commandCount(kClose) >= 1 && !robot.sessionOpen(); },
      1.0, drive))
      << "VEL " << robot.setpoint().vel_mm_s << ", CLOSEs " << robot.commandCount(kClose);
}

TEST(PioneerConnection, APortThatEchoesIsNotARobot)
{
  // A loopback plug or a terminal echoes SYNC0, SYNC1 and a bare SYNC2: the handshake's echo steps pass,
  // the SYNC2 reply names no robot.
  biovision_common::PseudoTerminal loopback;
  std::atomic<bool> stop{false};
  std::thread echo([&] {
    while (!stop)
      loopback.write(loopback.read(256, 0.01));
  });
  PioneerParameters p;
  p.port = loopback.slavePath();
  p.baud = 115200;
  p.reconnect_period = 0.2;
  PioneerConnection c(p);
  spinUntil(
      c, nullptr, [] { return false; }, 1.0);
  stop = true;
  echo.join();
  EXPECT_EQ(c.status().connects, 0u) << "an echo taken for a robot";
  EXPECT_NE(c.status().last_error.find("no robot name"), std::string::npos) << c.status().last_error;
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
