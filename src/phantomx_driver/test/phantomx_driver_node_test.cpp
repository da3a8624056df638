// rostest: the phantomx_driver node (real roscore, the real URDF's limits) against the AX-12 bus emulator
// hosted here on a pty.
#include <gtest/gtest.h>

#include <cmath>

#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>

#include "biovision_ros_common/rostest_helpers.hpp"
#include "phantomx_driver/ax12_bus_emulator.hpp"
#include "phantomx_driver/ax12_joint.hpp"

using biovision_ros_common::DiagnosticsWatch;
using biovision_ros_common::jointPosition;
using biovision_ros_common::TopicProbe;
using biovision_ros_common::waitFor;
using phantomx_driver::Ax12Joint;

namespace
{
std::unique_ptr<phantomx_driver::Ax12BusEmulator> g_servos;

class PhantomXDriverNode : public ::testing::Test
{
protected:
  PhantomXDriverNode()
  {
    pan_pub_ = nh_.advertise<std_msgs::Float64>("head_pan_joint/command", 10, true);
    tilt_pub_ = nh_.advertise<std_msgs::Float64>("head_tilt_joint/command", 10, true);
    spinner_.start();
  }
  void command(ros::Publisher& pub, double rad)
  {
    std_msgs::Float64 m;
    m.data = rad;
    pub.publish(m);
  }
  ros::NodeHandle nh_;
  ros::AsyncSpinner spinner_{2};
  ros::Publisher pan_pub_, tilt_pub_;
};
}  // namespace

TEST_F(PhantomXDriverNode, JointStatesAtThirtyHertzOrMoreAndTheyFollowTheCommands)
{
  TopicProbe<sensor_msgs::JointState> js(nh_, "joint_states");
  ASSERT_TRUE(waitFor([&] { return js.last() && js.last()->name.size() == 2; }, 15.0)) << "no joint_states";
  const size_t n0 = js.count();
  ros::WallDuration(1.0).sleep();
  EXPECT_GE(js.count() - n0, 30u) << "joint_states at >= 30 Hz";
  command(pan_pub_, 0.6);
  command(tilt_pub_, -0.3);
  ASSERT_TRUE(waitFor(
      [&] {
        return std::abs(jointPosition(js.last(), "head_pan_joint") - 0.6) < 0.01 &&
               std::abs(jointPosition(js.last(), "head_tilt_joint") + 0.3) < 0.01;
      },
      3.0))
      << jointPosition(js.last(), "head_pan_joint") << " " << jointPosition(js.last(), "head_tilt_joint");
  EXPECT_NEAR(g_servos->position(1), 512 + 0.6 / Ax12Joint::kRadPerTick, 1.0);
}

TEST_F(PhantomXDriverNode, CommandsBeyondTheUrdfLimitsStopAtTheLimits)
{
  TopicProbe<sensor_msgs::JointState> js(nh_, "joint_states");
  ASSERT_TRUE(waitFor([&] { return js.last() && js.last()->name.size() == 2; }, 15.0));
  command(pan_pub_, 3.0);    // URDF pan limit 1.5708
  command(tilt_pub_, -2.0);  // URDF tilt limit -0.7854
  ASSERT_TRUE(waitFor(
      [&] {
        return std::abs(jointPosition(js.last(), "head_pan_joint") - 1.5708) < 0.01 &&
               std::abs(jointPosition(js.last(), "head_tilt_joint") + 0.7854) < 0.01;
      },
      4.0));
  EXPECT_LE(g_servos->goalRange(1).second, static_cast<int>(std::lround(512 + 1.5708 / Ax12Joint::kRadPerTick)));
  EXPECT_GE(g_servos->goalRange(2).first, static_cast<int>(std::lround(512 - 0.7854 / Ax12Joint::kRadPerTick)));
  command(pan_pub_, NAN);  // ignored
  ros::WallDuration(0.3).sleep();
  EXPECT_NEAR(jointPosition(js.last(), "head_pan_joint"), 1.5708, 0.01);
  command(pan_pub_, 0.0);
  command(tilt_pub_, 0.0);
}

TEST_F(PhantomXDriverNode, ALostServoIsAnErrorAndTheOtherKeepsPublishing)
{
  DiagnosticsWatch diagnostics(nh_, "PhantomX head");
  TopicProbe<sensor_msgs::JointState> js(nh_, "joint_states");
  ASSERT_TRUE(waitFor([&] { return js.last() && js.last()->name.size() == 2; }, 15.0));
  g_servos->setSilent(2, true);
  ASSERT_TRUE(waitFor([&] { return js.last()->name.size() == 1; }, 2.0));
  EXPECT_EQ(js.last()->name[0], "head_pan_joint");
  // Wait for this error's message: an earlier test's bad command can still be the status's ERROR for a while.
  ASSERT_TRUE(waitFor([&] { return diagnostics.lastMessage().find("head_tilt_joint") != std::string::npos; }, 4.0))
      << diagnostics.lastMessage();
  EXPECT_TRUE(diagnostics.sawError());
  command(pan_pub_, -0.4);
  EXPECT_TRUE(waitFor([&] { return std::abs(jointPosition(js.last(), "head_pan_joint") + 0.4) < 0.01; }, 3.0));
  g_servos->setSilent(2, false);
  EXPECT_TRUE(waitFor([&] { return js.last()->name.size() == 2; }, 3.0)) << "the tilt servo is found again";
}

TEST_F(PhantomXDriverNode, APulledCableIsAnErrorThenTheBusIsReopened)
{
  DiagnosticsWatch diagnostics(nh_, "PhantomX head");
  TopicProbe<sensor_msgs::JointState> js(nh_, "joint_states");
  ASSERT_TRUE(waitFor([&] { return js.last() && js.last()->name.size() == 2; }, 15.0));
  g_servos->pullCable();
  ASSERT_TRUE(waitFor([&] { return diagnostics.lastMessage().find("port down") != std::string::npos; }, 4.0))
      << diagnostics.lastMessage();
  g_servos->plugIn();
  const size_t n = js.count();
  EXPECT_TRUE(js.waitForCount(n + 20, 5.0)) << "joint_states again after reconnecting";
}

TEST_F(PhantomXDriverNode, AnOverloadSwitchesTheTorqueOffWithAnError)
{
  DiagnosticsWatch diagnostics(nh_, "PhantomX head");
  TopicProbe<sensor_msgs::JointState> js(nh_, "joint_states");
  ASSERT_TRUE(waitFor([&] { return js.last() && js.last()->name.size() == 2; }, 15.0));
  g_servos->injectError(1, phantomx_driver::kErrorOverload);
  ASSERT_TRUE(waitFor([&] { return diagnostics.lastMessage().find("overload") != std::string::npos; }, 4.0))
      << diagnostics.lastMessage();
  EXPECT_TRUE(diagnostics.sawError());
  const int goal = g_servos->goal(1);
  command(pan_pub_, 0.9);
  ros::WallDuration(0.5).sleep();
  EXPECT_EQ(g_servos->goal(1), goal) << "no goal to a servo whose torque is off";
  EXPECT_FALSE(g_servos->torqueOn(1));
}

int main(int argc, char** argv)
{
  biovision_ros_common::RosTestRun tests(argc, argv, "phantomx_driver_node_test", 0);  // the fixtures spin
  std::string port;
  ros::NodeHandle("~").param<std::string>("port", port, "/tmp/biovision_rostest_phantomx");
  g_servos = std::make_unique<phantomx_driver::Ax12BusEmulator>(std::vector<uint8_t>{1, 2}, port);
  const int result = tests.run();
  g_servos.reset();
  return result;
}
