// Integration test of the simulator: topics at their rates (in sim time, over >= 20 frames: 2 s of camera
// time), the rectified stereo pair from the upstream image_proc nodelets, a tf tree that matches the camera
// model, the head following a command within its limits, the base following cmd_vel.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <vector>

#include <biovision_ros_common/rostest_helpers.hpp>
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
// Stamps of one topic. The rate is 1 / the median stamp interval, so one frame that a loaded machine's
// rectify nodelet drops does not read as a slower camera; missed() counts the frames the stamps skipped.
class Counter
{
public:
  void tick(const ros::Time& stamp)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stamps_.size() < kMaxStamps)
      stamps_.push_back(stamp.toSec());
    ++count_;
  }
  double rate() const
  {
    const double dt = medianInterval();
    return dt > 0 ? 1.0 / dt : 0.0;
  }
  // Frames missing between the first and last stamp, at the median interval.
  int missed() const
  {
    const double dt = medianInterval();
    std::lock_guard<std::mutex> lock(mutex_);
    if (dt <= 0 || stamps_.size() < 2)
      return 0;
    const double span = stamps_.back() - stamps_.front();
    return static_cast<int>(std::lround(span / dt)) + 1 - static_cast<int>(stamps_.size());
  }
  int count() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return count_;
  }

private:
  double medianInterval() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stamps_.size() < 2)
      return 0.0;
    std::vector<double> dt;
    for (size_t i = 1; i < stamps_.size(); ++i)
      dt.push_back(stamps_[i] - stamps_[i - 1]);
    std::nth_element(dt.begin(), dt.begin() + dt.size() / 2, dt.end());
    return dt[dt.size() / 2];
  }
  static constexpr size_t kMaxStamps = 1000;
  mutable std::mutex mutex_;
  int count_ = 0;
  std::vector<double> stamps_;
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
  sensor_msgs::CameraInfo right_info;
  std::mutex info_mutex;
  std::atomic<double> pan{0.0};
  std::atomic<double> odom_x{0.0};
  // Declared after everything its callbacks touch, so it is destroyed (unsubscribing, which waits for a
  // callback in progress) before they are: the other order let a spinner thread write into a destroyed
  // CameraInfo after the test body returned, before gtest wrote its result file.
  std::vector<ros::Subscriber> subs;
  for (const auto& t : image_topics)
    subs.push_back(nh.subscribe<sensor_msgs::Image>(t, 5, [&counters, t](const sensor_msgs::ImageConstPtr& m) {
      counters.at(t).tick(m->header.stamp);
    }));
  subs.push_back(nh.subscribe<sensor_msgs::CameraInfo>("stereo/right/camera_info", 5,
                                                       [&](const sensor_msgs::CameraInfoConstPtr& m) {
                                                         counters.at("info").tick(m->header.stamp);
                                                         std::lock_guard<std::mutex> lock(info_mutex);
                                                         right_info = *m;
                                                       }));
  subs.push_back(
      nh.subscribe<sensor_msgs::JointState>("joint_states", 50, [&](const sensor_msgs::JointStateConstPtr& m) {
        counters.at("joints").tick(m->header.stamp);
        const double p = biovision_ros_common::jointPosition(m, "head_pan_joint");
        if (!std::isnan(p))
          pan = p;
      }));
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
  // The simulator publishes every frame (its clock waits for it); the upstream rectify nodelets may drop
  // one when the machine is loaded (their queues are short), not one in five.
  for (const auto& t : image_topics)
  {
    const Counter& c = counters.at(t);
    EXPECT_NEAR(c.rate(), 10.0, 0.5) << t;
    EXPECT_LE(c.missed(), c.count() / (t.find("raw") != std::string::npos ? 10 : 5))
        << t << ": " << c.count() << " frames";
  }
  EXPECT_NEAR(counters.at("joints").rate(), 50.0, 2.5);
  EXPECT_NEAR(counters.at("odom").rate(), 50.0, 2.5);

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
  return biovision_ros_common::RosTestRun(argc, argv, "sim_node_test", 2).run();
}
