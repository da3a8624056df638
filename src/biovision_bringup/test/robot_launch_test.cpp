// rostest: robot.launch against the pioneer and phantomx emulators and a recorded camera frame: the drivers
// speak the simulator's topics, so the stack's wiring is the same as in sim.launch.
#include <gtest/gtest.h>

#include <cmath>

#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>
#include <tf2_ros/transform_listener.h>

#include "biovision_ros_common/rostest_helpers.hpp"

using biovision_ros_common::jointPosition;
using biovision_ros_common::TopicProbe;
using biovision_ros_common::waitFor;

TEST(RobotLaunch, TheDriversPublishTheSimulatorsTopicsAndTakeItsCommands)
{
  ros::NodeHandle nh;
  TopicProbe<nav_msgs::Odometry> odom(nh, "odom");
  TopicProbe<sensor_msgs::JointState> joints(nh, "joint_states");
  TopicProbe<sensor_msgs::Image> rectified(nh, "stereo/left/image_rect_color");
  ros::Publisher cmd = nh.advertise<geometry_msgs::Twist>("cmd_vel", 10);
  ros::Publisher pan = nh.advertise<std_msgs::Float64>("head_pan_joint/command", 10, true);
  ASSERT_TRUE(odom.waitForCount(5, 30.0)) << "no odom from pioneer_driver";
  ASSERT_TRUE(waitFor([&] { return joints.last() && joints.last()->name.size() == 2; }, 15.0))
      << "no joint_states from phantomx_driver";
  ASSERT_TRUE(rectified.waitForCount(2, 15.0)) << "no rectified images from the camera driver + stereo_proc";
  EXPECT_EQ(rectified.last()->width, 64u);

  std_msgs::Float64 angle;
  angle.data = 0.5;
  pan.publish(angle);
  EXPECT_TRUE(waitFor([&] { return std::abs(jointPosition(joints.last(), "head_pan_joint") - 0.5) < 0.01; }, 5.0))
      << jointPosition(joints.last(), "head_pan_joint");

  geometry_msgs::Twist t;
  t.linear.x = 0.2;
  EXPECT_TRUE(waitFor(
      [&] {
        cmd.publish(t);
        return std::abs(odom.last()->twist.twist.linear.x - 0.2) < 0.01;
      },
      5.0))
      << "cmd_vel does not reach the base";

  // robot_state_publisher turns joint_states into tf: the camera is reachable from odom.
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  EXPECT_TRUE(buffer.canTransform("odom", "stereo_left_optical", ros::Time(0), ros::Duration(5.0)));
  EXPECT_TRUE(buffer.canTransform("map", "base_link", ros::Time(0), ros::Duration(2.0)));
}

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "robot_launch_test", 2).run();
}
