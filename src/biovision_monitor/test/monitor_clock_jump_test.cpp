// monitor_panel on sim time: after ROS time jumps back (a looped bag, a restarted simulator) the panel
// forgets what it had (the head attractor tile returns to "no data"), and draws new input again.
#include <atomic>
#include <cmath>
#include <thread>

#include <biovision_msgs/AttractorState.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/Image.h>

#include "biovision_ros_common/rostest_helpers.hpp"

using biovision_ros_common::TopicProbe;
using biovision_ros_common::waitFor;

namespace
{
// Whether the head attractor tile (second row, third column) of the panel shows a plot (white background)
// rather than the dark "no data" tile.
bool headTileDrawn(const sensor_msgs::Image& m)
{
  const uint8_t* p = &m.data[size_t(242 + 120) * m.step + size_t(2 * 322 + 160) * 3];
  return p[0] > 200 && p[1] > 200 && p[2] > 200;
}
}  // namespace

TEST(MonitorClockJump, ABackwardJumpForgetsTheInputs)
{
  ros::NodeHandle nh;
  ros::Publisher clock_pub = nh.advertise<rosgraph_msgs::Clock>("/clock", 1);
  ros::Publisher head_pub = nh.advertise<biovision_msgs::AttractorState>("attractor/head", 1);
  std::atomic<double> now{100.0};
  std::atomic<bool> running{true};
  std::thread clock([&] {
    while (running && ros::ok())
    {
      rosgraph_msgs::Clock c;
      c.clock = ros::Time(now.load());
      clock_pub.publish(c);
      now = now + 0.05;
      ros::WallDuration(0.05).sleep();
    }
  });
  TopicProbe<sensor_msgs::Image> panel(nh, "monitor/panel", 3);
  biovision_ros_common::DiagnosticsWatch diagnostics(nh, "monitor panel");
  ASSERT_TRUE(waitFor([&] { return head_pub.getNumSubscribers() > 0; }, 15.0));
  biovision_msgs::AttractorState s;
  s.controller = "head_pan";
  s.section_angles = {0.0f};
  s.attraction = {1.0f};
  s.repulsion = {0.0f};
  s.forcelet = {0.0f};
  head_pub.publish(s);
  EXPECT_TRUE(waitFor([&] { return panel.last() && headTileDrawn(*panel.last()); }, 10.0)) << "no head plot";

  const size_t before = panel.count();
  now = 10.0;  // back by 90 s
  EXPECT_TRUE(waitFor([&] { return panel.last() && !headTileDrawn(*panel.last()); }, 10.0))
      << "the panel still shows the head state from before the jump (" << panel.count() - before
      << " panels since, the last stamped " << panel.last()->header.stamp.toSec()
      << "; diagnostics: " << diagnostics.lastMessage() << ")";
  ros::WallDuration(1.5).sleep();
  head_pub.publish(s);
  EXPECT_TRUE(waitFor([&] { return panel.last() && headTileDrawn(*panel.last()); }, 10.0))
      << "no head plot after the jump";
  running = false;
  clock.join();
}

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "test_monitor_clock_jump", 2).run();
}
