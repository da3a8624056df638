// Closed loop in the simulator: saliency -> attractor dynamics -> pan servo -> rendered camera.
// Within a fixed sim time the head fixates at least 3 different objects, visits both sides and never
// commands beyond the joint limits. Fixated objects come from the simulator's ground truth.
#include <atomic>
#include <deque>
#include <cmath>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include <biovision_ros_common/rostest_helpers.hpp>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>
#include <urdf/model.h>
#include <visualization_msgs/MarkerArray.h>

namespace
{
struct Object
{
  std::string label;
  double direction;  // pan angle that points the camera at it [rad]
};
}  // namespace

TEST(ClosedLoop, HeadExploresTheTableTop)
{
  ros::NodeHandle nh;
  urdf::Model model;
  ASSERT_TRUE(model.initParam("robot_description"));
  const auto pan_joint = model.getJoint("head_pan_joint");
  const double lower = pan_joint->limits->lower, upper = pan_joint->limits->upper;

  std::mutex mutex;
  std::vector<Object> objects;
  ros::Subscriber objects_sub = nh.subscribe<visualization_msgs::MarkerArray>(
      "sim/objects", 1, [&](const visualization_msgs::MarkerArrayConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex);
        objects.clear();
        for (const auto& k : m->markers)
          if (k.ns.rfind("wall", 0) != 0 && k.ns != "table")
            // The pan axis sits 0.05 m ahead of base_link (biovision_description).
            objects.push_back({k.ns, std::atan2(k.pose.position.y, k.pose.position.x - 0.05)});
      });
  std::atomic<bool> beyond{false};
  std::atomic<int> commands{0};
  ros::Subscriber cmd_sub = nh.subscribe<std_msgs::Float64>("head_pan_joint/command", 20,
                                                            [&](const std_msgs::Float64ConstPtr& m) {
                                                              ++commands;
                                                              if (!(m->data >= lower - 1e-9 && m->data <= upper + 1e-9))
                                                                beyond = true;
                                                            });
  std::vector<std::string> fixations;
  bool left = false, right = false;
  double max_pan = -10, min_pan = 10, last_fixation_t = -1e9;
  std::deque<std::pair<double, double>> window;  // (t, pan) over the last second
  ros::Subscriber js_sub = nh.subscribe<sensor_msgs::JointState>(
      "joint_states", 100, [&](const sensor_msgs::JointStateConstPtr& m) {
        const double pan = biovision_ros_common::jointPosition(m, "head_pan_joint");
        if (std::isnan(pan))
          return;
        const double t = m->header.stamp.toSec();
        std::lock_guard<std::mutex> lock(mutex);
        max_pan = std::max(max_pan, pan);
        min_pan = std::min(min_pan, pan);
        left |= pan > 0.17;
        right |= pan < -0.17;
        window.emplace_back(t, pan);
        while (!window.empty() && window.front().first < t - 1.0)
          window.pop_front();
        double lo = 10, hi = -10, sum = 0;
        for (const auto& w : window)
        {
          lo = std::min(lo, w.second);
          hi = std::max(hi, w.second);
          sum += w.second;
        }
        // A fixation: the head stays within +-5 deg for a second.
        if (t - window.front().first >= 0.95 && hi - lo < 0.17 && t - last_fixation_t > 1.0)
        {
          const double at = sum / window.size();
          const Object* best = nullptr;
          for (const auto& o : objects)
            if (!best || std::abs(o.direction - at) < std::abs(best->direction - at))
              best = &o;
          // The object the camera points at, if within 12 deg.
          if (best && std::abs(best->direction - at) < 0.21 && (fixations.empty() || fixations.back() != best->label))
            fixations.push_back(best->label);
          last_fixation_t = t;
        }
      });

  // Run for 80 s of sim time.
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(200);
  ros::Time start;
  while (ros::ok() && ros::WallTime::now() < deadline)
  {
    ros::WallDuration(0.2).sleep();
    const ros::Time now = ros::Time::now();
    if (now.isZero())
      continue;
    if (start.isZero())
      start = now;
    if ((now - start).toSec() > 80.0)
      break;
  }
  std::lock_guard<std::mutex> lock(mutex);
  std::string order;
  for (const auto& f : fixations)
    order += f + " ";
  const std::set<std::string> distinct(fixations.begin(), fixations.end());
  EXPECT_GT(commands.load(), 100) << "the head controller did not command the head";
  EXPECT_GE(distinct.size(), 3u) << "fixated: " << order << " (pan range " << min_pan << " .. " << max_pan << ")";
  EXPECT_TRUE(left && right) << "visited left " << left << ", right " << right;
  EXPECT_FALSE(beyond.load()) << "a pan command was beyond the joint limits";
  std::printf("closed loop: fixations in order: %s\n", order.c_str());
}

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "closed_loop_test", 2).run();
}
