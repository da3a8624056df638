// rostest: the head controller turns the emulated PhantomX through the real driver, and joint_states
// (read back from the servos) follows: the hardware path of the active-vision loop.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include <biovision_msgs/SalientRegionArray.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>

#include "biovision_ros_common/rostest_helpers.hpp"

using biovision_ros_common::jointPosition;
using biovision_ros_common::TopicProbe;
using biovision_ros_common::waitFor;

TEST(HeadLoop, TheHeadControllerTurnsTheEmulatedServosTowardsASalientObject)
{
  ros::NodeHandle nh;
  TopicProbe<sensor_msgs::JointState> joints(nh, "joint_states");
  TopicProbe<std_msgs::Float64> commands(nh, "head_pan_joint/command", 100000);
  ros::Publisher regions = nh.advertise<biovision_msgs::SalientRegionArray>("saliency/regions", 10);
  ASSERT_TRUE(waitFor([&] { return joints.last() && joints.last()->name.size() == 2; }, 20.0))
      << "no joint_states from the driver";
  const double object = 0.3;  // rad, inside the 43° view of a head looking ahead
  double closest = 1e9;
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(8.0);
  while (ros::WallTime::now() < end)
  {
    const double pan = jointPosition(joints.last(), "head_pan_joint");
    biovision_msgs::SalientRegionArray msg;
    msg.header.stamp = ros::Time::now();
    if (std::abs(object - pan) < 0.37)  // the object is seen while it is in the field of view
    {
      biovision_msgs::SalientRegion r;
      r.pan = static_cast<float>(object);
      r.tilt = 0.0f;
      r.peak_saliency = 0.9f;
      r.area = 1000;
      msg.regions.push_back(r);
    }
    regions.publish(msg);
    closest = std::min(closest, std::abs(pan - object));
    ros::WallDuration(0.1).sleep();
  }
  EXPECT_LT(closest, 0.05) << "the head never reached the object (closest " << closest << " rad)";
  ASSERT_GT(commands.count(), 10u);
  for (const auto& c : commands.messages())
    EXPECT_LE(std::abs(c->data), 1.5708 + 1e-9) << "a command beyond the URDF limit";
}

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "head_loop_test", 2).run();
}
