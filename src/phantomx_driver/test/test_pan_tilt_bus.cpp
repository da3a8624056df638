// The real bus driver against the AX-12 bus emulator over a pseudo-terminal.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <functional>

#include "phantomx_driver/ax12_bus_emulator.hpp"
#include "phantomx_driver/pan_tilt_bus.hpp"

using namespace phantomx_driver;

namespace
{
double now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

bool stepUntil(PanTiltBus& bus, const std::function<bool()>& done, double seconds)
{
  const double end = now() + seconds;
  while (now() < end)
  {
    bus.step(now());
    if (done())
      return true;
    usleep(5000);
  }
  return done();
}

PhantomXParameters parametersFor(const Ax12BusEmulator& emulator)
{
  PhantomXParameters p;
  p.port = emulator.port();
  p.retry_period = 0.2;
  return p;
}
}  // namespace

TEST(PanTiltBus, FindsBothServosAndReadsTheirState)
{
  Ax12BusEmulator servos;
  PanTiltBus bus(parametersFor(servos));
  ASSERT_TRUE(stepUntil(
      bus, [&] { return bus.servo(0).alive && bus.servo(1).alive; }, 2.0))
      << bus.lastError();
  EXPECT_NEAR(bus.servo(0).position, 0.0, 1e-9);
  EXPECT_NEAR(bus.servo(0).voltage, 12.0, 1e-9);
  EXPECT_EQ(bus.servo(0).temperature, 35);
  EXPECT_TRUE(servos.torqueOn(1));
  EXPECT_EQ(servos.movingSpeed(1), movingSpeedTicks(3.0));
}

TEST(PanTiltBus, AStaleGoalRegisterDoesNotMakeTheServoJumpWhenTorqueComesOn)
{
  Ax12BusEmulator servos;
  servos.setRegister16(1, kAddrGoalPosition, 900);  // left over from an earlier session, torque still off
  PanTiltBus bus(parametersFor(servos));
  ASSERT_TRUE(stepUntil(
      bus, [&] { return bus.servo(0).alive && servos.torqueOn(1); }, 2.0));
  EXPECT_EQ(servos.goal(1), 512) << "the goal is set to where the servo is before torque on";
  stepUntil(
      bus, [] { return false; }, 0.3);
  EXPECT_NEAR(servos.position(1), 512.0, 0.5);
}

TEST(PanTiltBus, GoalsGoOutBySyncWriteAndPositionsFollowWithinTheLimits)
{
  Ax12BusEmulator servos;
  PanTiltBus bus(parametersFor(servos));
  ASSERT_TRUE(stepUntil(
      bus, [&] { return bus.servo(0).alive && bus.servo(1).alive; }, 2.0));
  EXPECT_TRUE(bus.setGoal(PanTiltBus::kPan, 0.5));
  EXPECT_FALSE(bus.setGoal(PanTiltBus::kTilt, 2.0)) << "beyond the tilt limit: clamped";
  ASSERT_TRUE(stepUntil(
      bus,
      [&] { return std::abs(bus.servo(0).position - 0.5) < 0.01 && std::abs(bus.servo(1).position - 0.7854) < 0.01; },
      3.0))
      << bus.servo(0).position << " " << bus.servo(1).position;
  EXPECT_GE(servos.syncWrites(), 1u);
  EXPECT_LE(servos.goalRange(2).second, bus.joint(1).goalTicks(0.7854));
  EXPECT_FALSE(bus.setGoal(PanTiltBus::kPan, NAN));
  bus.setLimits(PanTiltBus::kPan, -0.2, 0.2);  // e.g. a narrower URDF
  bus.setGoal(PanTiltBus::kPan, -1.0);
  ASSERT_TRUE(stepUntil(
      bus, [&] { return std::abs(bus.servo(0).position + 0.2) < 0.01; }, 3.0));
  EXPECT_GE(servos.goalRange(1).first, bus.joint(0).goalTicks(-0.2));
}

TEST(PanTiltBus, ALostSyncWriteIsNoticedAndTheGoalWrittenAgain)
{
  Ax12BusEmulator servos;
  PanTiltBus bus(parametersFor(servos));
  ASSERT_TRUE(stepUntil(
      bus, [&] { return bus.servo(0).alive && bus.servo(1).alive; }, 2.0));
  servos.dropNextSyncWrites(1);  // the broadcast carrying the new goals never arrives
  bus.setGoal(PanTiltBus::kPan, 0.5);
  bus.setGoal(PanTiltBus::kTilt, 0.3);
  ASSERT_TRUE(stepUntil(
      bus, [&] { return std::abs(bus.servo(0).position - 0.5) < 0.01 && std::abs(bus.servo(1).position - 0.3) < 0.01; },
      3.0))
      << "the head stayed where it was: " << bus.servo(0).position << " " << bus.servo(1).position;
  EXPECT_EQ(bus.servo(0).goal_rewrites, 1u);
  EXPECT_EQ(bus.servo(1).goal_rewrites, 1u);
}

TEST(PanTiltBus, AGoalTheServoDoesNotKeepIsWrittenAFewTimesThenLeftWithAnError)
{
  Ax12BusEmulator servos;
  PanTiltBus bus(parametersFor(servos));
  ASSERT_TRUE(stepUntil(
      bus, [&] { return bus.servo(0).alive && bus.servo(1).alive; }, 2.0));
  servos.dropNextSyncWrites(1000);  // as a servo whose angle limits refuse every new goal
  bus.setGoal(PanTiltBus::kPan, 0.5);
  stepUntil(
      bus, [] { return false; }, 0.5);
  EXPECT_EQ(bus.servo(0).goal_rewrites, static_cast<unsigned long>(PanTiltBus::kMaxGoalRewrites)) << "not a loop";
  EXPECT_NE(bus.lastError().find("does not keep goal"), std::string::npos) << bus.lastError();
  servos.dropNextSyncWrites(0);
  bus.setGoal(PanTiltBus::kPan, 0.3);  // a new goal is tried again
  ASSERT_TRUE(stepUntil(
      bus, [&] { return std::abs(bus.servo(0).position - 0.3) < 0.01; }, 3.0));
}

TEST(PanTiltBus, APositionBeyondTenBitsIsNotBelieved)
{
  Ax12BusEmulator servos;
  PanTiltBus bus(parametersFor(servos));
  ASSERT_TRUE(stepUntil(
      bus, [&] { return bus.servo(0).alive && bus.servo(1).alive; }, 2.0));
  const unsigned long misses = bus.servo(0).misses;
  servos.misreportPosition(1, 65535, 1);  // checksum intact
  stepUntil(
      bus, [] { return false; }, 0.2);
  EXPECT_EQ(bus.servo(0).misses, misses + 1);
  EXPECT_TRUE(bus.servo(0).alive) << "one bad reply is a miss, not a lost servo";
  EXPECT_NEAR(bus.servo(0).position, 0.0, 1e-9) << "332 rad would have been published";
  EXPECT_NE(bus.lastError().find("outside 0-1023"), std::string::npos) << bus.lastError();
}

TEST(PanTiltBus, AnOverloadSwitchesThatServosTorqueOff)
{
  Ax12BusEmulator servos;
  PanTiltBus bus(parametersFor(servos));
  ASSERT_TRUE(stepUntil(
      bus, [&] { return bus.servo(0).alive && bus.servo(1).alive; }, 2.0));
  servos.injectError(2, kErrorOverload | kErrorOverheat);
  ASSERT_TRUE(stepUntil(
      bus, [&] { return bus.servo(1).torque_off; }, 2.0));
  EXPECT_EQ(describeErrorBits(bus.servo(1).error), "overheat, overload");
  EXPECT_NE(bus.lastError().find("overload"), std::string::npos);
  EXPECT_FALSE(servos.torqueOn(2));
  bus.setGoal(PanTiltBus::kTilt, 0.3);
  bus.setGoal(PanTiltBus::kPan, 0.3);
  ASSERT_TRUE(stepUntil(
      bus, [&] { return std::abs(bus.servo(0).position - 0.3) < 0.01; }, 3.0));
  EXPECT_EQ(servos.goal(2), 512) << "no goal to a servo switched off";
  EXPECT_FALSE(servos.torqueOn(2));
}

TEST(PanTiltBus, ALostServoIsReportedAndTheOtherKeepsWorking)
{
  Ax12BusEmulator servos;
  PanTiltBus bus(parametersFor(servos));
  ASSERT_TRUE(stepUntil(
      bus, [&] { return bus.servo(0).alive && bus.servo(1).alive; }, 2.0));
  servos.setSilent(1, true);
  ASSERT_TRUE(stepUntil(
      bus, [&] { return !bus.servo(0).alive; }, 2.0));
  EXPECT_NE(bus.lastError().find("does not answer"), std::string::npos) << bus.lastError();
  bus.setGoal(PanTiltBus::kTilt, -0.4);
  ASSERT_TRUE(stepUntil(
      bus, [&] { return std::abs(bus.servo(1).position + 0.4) < 0.01; }, 3.0));
  servos.setSilent(1, false);
  ASSERT_TRUE(stepUntil(
      bus, [&] { return bus.servo(0).alive; }, 2.0))
      << "found again after retry_period";
}

TEST(PanTiltBus, CorruptedRepliesAreRejectedNotBelieved)
{
  Ax12BusEmulator servos;
  PanTiltBus bus(parametersFor(servos));
  ASSERT_TRUE(stepUntil(
      bus, [&] { return bus.servo(0).alive && bus.servo(1).alive; }, 2.0));
  servos.corruptNextReplies(2);
  ASSERT_TRUE(stepUntil(
      bus, [&] { return bus.rejectedPackets() >= 2; }, 2.0));
  EXPECT_TRUE(stepUntil(
      bus, [&] { return bus.servo(0).alive && bus.servo(1).alive; }, 1.0))
      << "two bad replies are fewer than lost_after";
  EXPECT_EQ(servos.badChecksums(), 0u) << "the driver's packets are all correct";
}

TEST(PanTiltBus, APulledCableClosesThePortAndItIsReopened)
{
  const std::string link = "/tmp/biovision_phantomx_gtest_" + std::to_string(::getpid());
  Ax12BusEmulator servos({1, 2}, link);
  PanTiltBus bus(parametersFor(servos));
  ASSERT_TRUE(stepUntil(
      bus, [&] { return bus.servo(0).alive && bus.servo(1).alive; }, 2.0));
  servos.pullCable();
  ASSERT_TRUE(stepUntil(
      bus, [&] { return !bus.portOpen(); }, 2.0));
  EXPECT_FALSE(bus.servo(0).alive);
  EXPECT_FALSE(bus.lastError().empty());
  servos.plugIn();
  ASSERT_TRUE(stepUntil(
      bus, [&] { return bus.servo(0).alive && bus.servo(1).alive; }, 3.0))
      << bus.lastError();
  EXPECT_EQ(bus.portFailures(), 1u);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
