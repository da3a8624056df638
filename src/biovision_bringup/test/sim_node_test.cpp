// Integration test of the simulator: topics at their rates (in sim time, over 20 frames: 2 s of camera
// time), the rectified stereo pair from the upstream image_proc nodelets, a tf tree that matches the camera
// model, the head following a command within its limits, the base following cmd_vel.
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>

#include <geometry_msgs/Twist.h>
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>
#include <tf2_ros/transform_listener.h>
#include <urdf/model.h>

namespace
{
class Counter
{
public:
  void tick(const ros::Time& stamp)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (count_ == 0)
      first_ = stamp;
    last_ = stamp;
    ++count_;
  }
  double rate() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return count_ > 1 ? (count_ - 1) / (last_ - first_).toSec() : 0.0;
  }
  int count() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return count_;
  }

private:
  mutable std::mutex mutex_;
  int count_ = 0;
  ros::Time first_, last_;
};

template <typename Pred>
bool waitWall(Pred pred, double seconds)
{
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::ok() && ros::WallTime::now() < end && !pred())
    ros::WallDuration(0.05).sleep();
  return pred();
}
}  // namespace

TEST(Sim, TopicsRatesTfHeadAndBase)
{
  ros::NodeHandle nh;
  const std::vector<std::string> image_topics = {"stereo/left/image_raw", "stereo/right/image_raw",
                                                 "stereo/left/image_rect_color", "stereo/right/image_rect_color"};
  // Every counter exists before the first callback: the two spinner threads and this one only look them up
  // (inserting into a std::map from several threads at once is a data race).
  std::map<std::string, Counter> counters;
  for (const auto& name : image_topics)
    counters[name];
  for (const char* name : {"info", "joints", "odom"})
    counters[name];
  std::vector<ros::Subscriber> subs;
  for (const auto& t : image_topics)
    subs.push_back(nh.subscribe<sensor_msgs::Image>(t, 5, [&counters, t](const sensor_msgs::ImageConstPtr& m) {
      counters.at(t).tick(m->header.stamp);
    }));
  sensor_msgs::CameraInfo right_info;
  std::mutex info_mutex;
  subs.push_back(nh.subscribe<sensor_msgs::CameraInfo>("stereo/right/camera_info", 5,
                                                       [&](const sensor_msgs::CameraInfoConstPtr& m) {
                                                         counters.at("info").tick(m->header.stamp);
                                                         std::lock_guard<std::mutex> lock(info_mutex);
                                                         right_info = *m;
                                                       }));
  std::atomic<double> pan{0.0};
  subs.push_back(
      nh.subscribe<sensor_msgs::JointState>("joint_states", 50, [&](const sensor_msgs::JointStateConstPtr& m) {
        counters.at("joints").tick(m->header.stamp);
        for (size_t i = 0; i < m->name.size(); ++i)
          if (m->name[i] == "head_pan_joint")
            pan = m->position[i];
      }));
  std::atomic<double> odom_x{0.0};
  subs.push_back(nh.subscribe<nav_msgs::Odometry>("odom", 50, [&](const nav_msgs::OdometryConstPtr& m) {
    counters.at("odom").tick(m->header.stamp);
    odom_x = m->pose.pose.position.x;
  }));

  ASSERT_TRUE(waitWall(
      [&] {
        for (const auto& t : image_topics)
          if (counters.at(t).count() < 20)
            return false;
        return counters.at("joints").count() > 40 && counters.at("odom").count() > 40;
      },
      60.0))
      << "left raw " << counters.at("stereo/left/image_raw").count() << ", left rect "
      << counters.at("stereo/left/image_rect_color").count() << ", joints " << counters.at("joints").count();
  for (const auto& t : image_topics)
    EXPECT_NEAR(counters.at(t).rate(), 10.0, 1.5) << t;
  EXPECT_NEAR(counters.at("joints").rate(), 50.0, 5.0);
  EXPECT_NEAR(counters.at("odom").rate(), 50.0, 5.0);

  // tf (robot_state_publisher on the same URDF) and the cameras agree: baseline = P[3] / -fx.
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  geometry_msgs::TransformStamped lr;
  ASSERT_TRUE(waitWall(
      [&] {
        try
        {
          lr = buffer.lookupTransform("stereo_left_optical", "stereo_right_optical", ros::Time(0));
          buffer.lookupTransform("odom", "stereo_left_optical", ros::Time(0));
          return true;
        }
        catch (const tf2::TransformException&)
        {
          return false;
        }
      },
      20.0));
  {
    std::lock_guard<std::mutex> lock(info_mutex);
    EXPECT_NEAR(-right_info.P[3] / right_info.P[0], lr.transform.translation.x, 1e-6);
  }

  // The head follows a command and stops at the description's limit.
  urdf::Model model;
  ASSERT_TRUE(model.initParam("robot_description"));
  const double upper = model.getJoint("head_pan_joint")->limits->upper;
  ros::Publisher pan_pub = nh.advertise<std_msgs::Float64>("head_pan_joint/command", 1, true);
  std_msgs::Float64 cmd;
  cmd.data = 3.0;  // beyond the +90 deg limit
  pan_pub.publish(cmd);
  EXPECT_TRUE(waitWall([&] { return std::abs(pan - upper) < 1e-3; }, 20.0)) << "pan " << pan;
  ros::WallDuration(0.5).sleep();
  EXPECT_LE(pan, upper + 1e-9);

  // The base follows cmd_vel.
  ros::Publisher cmd_pub = nh.advertise<geometry_msgs::Twist>("cmd_vel", 1);
  geometry_msgs::Twist tw;
  tw.linear.x = 0.2;
  EXPECT_TRUE(waitWall(
      [&] {
        cmd_pub.publish(tw);
        return odom_x > 0.05;
      },
      20.0))
      << "odom x " << odom_x;
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "sim_node_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
