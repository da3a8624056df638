// Replaying a committed bag publishes the recorded topics on sim time, and the stereo front end turns
// the recorded raw pair into rectified images.
#include <atomic>
#include <string>
#include <vector>

#include <biovision_ros_common/rostest_helpers.hpp>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/transform_listener.h>

TEST(Replay, CommittedBagPublishesTheRecordedTopics)
{
  ros::NodeHandle nh;
  std::atomic<int> left_raw{0}, left_rect{0}, right_rect{0}, info{0}, joints{0};
  std::atomic<bool> sim_stamps{true};
  std::vector<ros::Subscriber> subs;
  subs.push_back(nh.subscribe<sensor_msgs::Image>("stereo/left/image_raw", 5, [&](const sensor_msgs::ImageConstPtr& m) {
    ++left_raw;
    sim_stamps = sim_stamps && m->header.stamp.toSec() < 1000;  // the simulator's clock starts at 1 s
  }));
  subs.push_back(nh.subscribe<sensor_msgs::Image>("stereo/left/image_rect_color", 5,
                                                  [&](const sensor_msgs::ImageConstPtr&) { ++left_rect; }));
  subs.push_back(nh.subscribe<sensor_msgs::Image>("stereo/right/image_rect_color", 5,
                                                  [&](const sensor_msgs::ImageConstPtr&) { ++right_rect; }));
  subs.push_back(nh.subscribe<sensor_msgs::CameraInfo>("stereo/left/camera_info", 5,
                                                       [&](const sensor_msgs::CameraInfoConstPtr&) { ++info; }));
  subs.push_back(nh.subscribe<sensor_msgs::JointState>("joint_states", 50,
                                                       [&](const sensor_msgs::JointStateConstPtr&) { ++joints; }));
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  bool tf_ok = false;
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(40);
  while (ros::ok() && ros::WallTime::now() < deadline)
  {
    ros::WallDuration(0.1).sleep();
    if (!tf_ok)
      tf_ok = buffer.canTransform("odom", "stereo_left_optical", ros::Time(0));
    if (left_rect >= 20 && right_rect >= 20 && joints >= 200 && tf_ok)
      break;
  }
  EXPECT_GE(left_raw.load(), 20);
  EXPECT_GE(left_rect.load(), 20) << "the stereo front end did not rectify the replayed images";
  EXPECT_GE(right_rect.load(), 20);
  EXPECT_GE(info.load(), 20);
  EXPECT_GE(joints.load(), 200);
  EXPECT_TRUE(tf_ok) << "recorded tf does not resolve odom -> stereo_left_optical";
  EXPECT_TRUE(sim_stamps.load());
}

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "replay_test", 2).run();
}
