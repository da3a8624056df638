// rostest: the pioneer_driver node (real roscore) against the ARCOS emulator hosted here on a pty.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <biovision_msgs/PioneerState.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <tf2_ros/transform_listener.h>

#include "biovision_ros_common/rostest_helpers.hpp"
#include "pioneer_driver/arcos_emulator.hpp"

using biovision_ros_common::DiagnosticsWatch;
using biovision_ros_common::TopicProbe;
using biovision_ros_common::waitFor;

namespace
{
std::unique_ptr<pioneer_driver::ArcosEmulator> g_robot;

class PioneerDriverNode : public ::testing::Test
{
protected:
  PioneerDriverNode()
  {
    cmd_pub_ = nh_.advertise<geometry_msgs::Twist>("cmd_vel", 10);
    spinner_.start();
  }
  /// Publishes cmd_vel at 20 Hz for `seconds`.
  void drive(double v, double w, double seconds)
  {
    geometry_msgs::Twist t;
    t.linear.x = v;
    t.angular.z = w;
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
    while (ros::WallTime::now() < end)
    {
      cmd_pub_.publish(t);
      ros::WallDuration(0.05).sleep();
    }
  }
  ros::NodeHandle nh_;
  ros::AsyncSpinner spinner_{2};
  ros::Publisher cmd_pub_;
};
}  // namespace

TEST_F(PioneerDriverNode, ConnectsAndPublishesOdometryTfAndState)
{
  TopicProbe<nav_msgs::Odometry> odom(nh_, "odom");
  TopicProbe<biovision_msgs::PioneerState> state(nh_, "pioneer_state");
  ASSERT_TRUE(odom.waitForCount(10, 15.0)) << "no odom from the emulator's SIPs";
  ASSERT_TRUE(state.waitForCount(1, 2.0));
  EXPECT_TRUE(state.last()->connected);
  EXPECT_TRUE(state.last()->motors_enabled);
  EXPECT_NEAR(state.last()->battery_voltage, 12.5, 1e-3);
  EXPECT_EQ(odom.last()->header.frame_id, "odom");
  EXPECT_EQ(odom.last()->child_frame_id, "base_link");
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  EXPECT_TRUE(buffer.canTransform("odom", "base_link", ros::Time(0), ros::Duration(2.0)));
}

TEST_F(PioneerDriverNode, CmdVelArrivesClampedAndOdomFollows)
{
  TopicProbe<nav_msgs::Odometry> odom(nh_, "odom");
  ASSERT_TRUE(odom.waitForCount(2, 15.0));
  const double x0 = odom.last()->pose.pose.position.x, y0 = odom.last()->pose.pose.position.y;
  drive(1.0, -3.0, 1.5);  // beyond the 0.4 m/s (test parameter) and 100°/s caps
  EXPECT_EQ(g_robot->setpoint().vel_mm_s, 400);
  EXPECT_EQ(g_robot->setpoint().rvel_deg_s, -99);
  EXPECT_LE(g_robot->maxAbsVel(), 400);
  EXPECT_LE(g_robot->maxAbsRvel(), 99);
  ros::WallDuration(0.3).sleep();
  EXPECT_GT(std::hypot(odom.last()->pose.pose.position.x - x0, odom.last()->pose.pose.position.y - y0), 0.1);
}

TEST_F(PioneerDriverNode, AGoToGoalLoopOnOdomReachesTheGoalInTheEmulatorsTruePose)
{
  // A stand-in for the base controller: turn towards the goal, drive, stop — on odom alone. Signs or
  // frames wrong anywhere (yaw, y, the origin at the first SIP) and it misses or circles.
  TopicProbe<nav_msgs::Odometry> odom(nh_, "odom");
  ASSERT_TRUE(odom.waitForCount(2, 15.0));
  const auto start = odom.last();
  const double gx = start->pose.pose.position.x + 0.4, gy = start->pose.pose.position.y + 0.3;
  const double true_x0 = g_robot->x(), true_y0 = g_robot->y();
  bool reached = false;
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(15.0);
  while (!reached && ros::WallTime::now() < end)
  {
    const auto o = odom.last();
    const double dx = gx - o->pose.pose.position.x, dy = gy - o->pose.pose.position.y;
    const double yaw = 2.0 * std::atan2(o->pose.pose.orientation.z, o->pose.pose.orientation.w);
    const double error = std::remainder(std::atan2(dy, dx) - yaw, 2.0 * M_PI);
    const double distance = std::hypot(dx, dy);
    geometry_msgs::Twist t;
    reached = distance < 0.03;
    if (!reached)
    {
      t.angular.z = std::clamp(2.0 * error, -1.0, 1.0);
      t.linear.x = std::abs(error) < 0.3 ? std::min(0.3, distance) : 0.0;
    }
    cmd_pub_.publish(t);
    ros::WallDuration(0.05).sleep();
  }
  ASSERT_TRUE(reached) << "the goal was not reached on odometry in 15 s";
  ASSERT_TRUE(waitFor([] { return g_robot->setpoint() == pioneer_driver::ArcosVelocity{}; }, 1.0));
  // The emulator's true displacement: the same 0.5 m (its pose frame is the controller's own, so compare
  // the length; the direction is the odometry test's).
  const double travelled = std::hypot(g_robot->x() - true_x0, g_robot->y() - true_y0);
  EXPECT_NEAR(travelled, 0.5, 0.06);
}

TEST_F(PioneerDriverNode, TheBaseStopsHalfASecondAfterTheLastCmdVel)
{
  TopicProbe<nav_msgs::Odometry> odom(nh_, "odom");
  ASSERT_TRUE(odom.waitForCount(2, 15.0));
  drive(0.2, 0.0, 0.5);
  ASSERT_EQ(g_robot->setpoint().vel_mm_s, 200);
  const ros::WallTime last = ros::WallTime::now();
  ASSERT_TRUE(waitFor([] { return g_robot->setpoint().vel_mm_s == 0; }, 3.0));
  const double after = (ros::WallTime::now() - last).toSec();
  std::printf("[ MEASURED ] stopped %.3f s after the last cmd_vel\n", after);
  EXPECT_GT(after, 0.35);
  EXPECT_LT(after, 1.0) << "the driver's 0.5 s time-out, not the robot's 2 s watchdog";
  ASSERT_TRUE(waitFor([&] { return std::abs(odom.last()->twist.twist.linear.x) < 1e-6; }, 1.0));
}

TEST_F(PioneerDriverNode, CorruptedSipsGiveADiagnosticsErrorAndOdomGoesOn)
{
  DiagnosticsWatch diagnostics(nh_, "Pioneer base");
  TopicProbe<nav_msgs::Odometry> odom(nh_, "odom");
  ASSERT_TRUE(odom.waitForCount(2, 15.0));
  ASSERT_TRUE(waitFor([&] { return diagnostics.received() > 0; }, 3.0));
  diagnostics.clear();
  g_robot->corruptNextSips(3);
  ASSERT_TRUE(waitFor([&] { return diagnostics.sawError(); }, 4.0)) << diagnostics.lastMessage();
  EXPECT_NE(diagnostics.lastMessage().find("rejected"), std::string::npos) << diagnostics.lastMessage();
  const size_t n = odom.count();
  EXPECT_TRUE(odom.waitForCount(n + 5, 2.0));
}

TEST_F(PioneerDriverNode, ReconfigureLowersTheCapAndClampsARequestBeyondTheRange)
{
  auto call = [](double max_linear_speed) {
    dynamic_reconfigure::Reconfigure srv;
    dynamic_reconfigure::DoubleParameter d;
    d.name = "max_linear_speed";
    d.value = max_linear_speed;
    srv.request.config.doubles.push_back(d);
    EXPECT_TRUE(ros::service::call("pioneer_driver/set_parameters", srv));
    for (const auto& p : srv.response.config.doubles)
      if (p.name == "max_linear_speed")
        return p.value;
    return -1.0;
  };
  EXPECT_DOUBLE_EQ(call(0.2), 0.2);
  drive(1.0, 0.0, 0.5);
  EXPECT_EQ(g_robot->setpoint().vel_mm_s, 200);
  EXPECT_DOUBLE_EQ(call(5.0), 2.2) << "the .cfg range clamps a request beyond the P3DX's 2.2 m/s";
  EXPECT_DOUBLE_EQ(call(0.2), 0.2);
}

TEST_F(PioneerDriverNode, APulledCableIsAnErrorThenTheDriverReconnects)
{
  DiagnosticsWatch diagnostics(nh_, "Pioneer base");
  TopicProbe<nav_msgs::Odometry> odom(nh_, "odom");
  TopicProbe<biovision_msgs::PioneerState> state(nh_, "pioneer_state");
  ASSERT_TRUE(odom.waitForCount(2, 15.0));
  g_robot->pullCable();
  ASSERT_TRUE(waitFor([&] { return diagnostics.lastMessage().find("disconnected") != std::string::npos; }, 4.0))
      << diagnostics.lastMessage();
  EXPECT_TRUE(diagnostics.sawError());
  const size_t n = odom.count();
  ros::WallDuration(1.0).sleep();
  EXPECT_LE(odom.count(), n + 1) << "no odometry while the cable is out";
  g_robot->plugIn();
  ASSERT_TRUE(odom.waitForCount(odom.count() + 5, 10.0)) << "no reconnection";
  EXPECT_TRUE(state.last()->connected);
  drive(0.1, 0.0, 0.5);
  EXPECT_EQ(g_robot->setpoint().vel_mm_s, 100) << "commands flow again after the reconnection";
}

int main(int argc, char** argv)
{
  biovision_ros_common::RosTestRun tests(argc, argv, "pioneer_driver_node_test", 0);  // the fixtures spin
  std::string port;
  ros::NodeHandle("~").param<std::string>("port", port, "/tmp/biovision_rostest_pioneer");
  g_robot = std::make_unique<pioneer_driver::ArcosEmulator>(port);
  const int result = tests.run();
  g_robot.reset();
  return result;
}
