// DisplayStatusPanel (the rviz plugin) reports rviz's own per-display status: with test/rviz_display_status.rviz
// under Xvfb, the Grid and an Image display fed the right type are Ok, an Image display on a topic of the
// wrong type (std_msgs/String) is not Ok, and a display whose class does not exist is in error. This is the
// failure the monitor_rviz rostest (biovision_bringup) relies on being seen.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/String.h>

#include "biovision_ros_common/rostest_helpers.hpp"

using biovision_ros_common::TopicProbe;
using biovision_ros_common::waitFor;

TEST(RvizDisplayStatus, MissingClassIsAnErrorWrongTopicTypeIsNotOkTheRestOk)
{
  ros::NodeHandle nh, pnh("~");
  std::string config;
  pnh.getParam("rviz_config", config);
  ASSERT_FALSE(config.empty());
  int number = 0;
  for (int n = 201; n < 300 && !number; ++n)
    if (access(("/tmp/.X" + std::to_string(n) + "-lock").c_str(), F_OK) != 0)
      number = n;
  ASSERT_GT(number, 0) << "no free X display number";
  const std::string display = ":" + std::to_string(number);
  biovision_ros_common::ChildProcess xvfb({"Xvfb", display, "-screen", "0", "800x600x24", "-nolisten", "tcp"});
  ros::WallDuration(1.0).sleep();
  biovision_ros_common::ChildProcess rviz({"rviz", "-d", config, "__name:=rviz_status_test"}, display);

  ros::Publisher right = nh.advertise<sensor_msgs::Image>("/right_type", 1);
  ros::Publisher wrong = nh.advertise<std_msgs::String>("/wrong_type", 1);
  TopicProbe<diagnostic_msgs::DiagnosticArray> status(nh, "/rviz_status_test/display_status", 5);
  std::map<std::string, int> levels;
  auto read = [&] {
    levels.clear();
    if (const auto a = status.last())
      for (const auto& s : a->status)
        levels[s.name] = s.level;
  };
  const bool settled = waitFor(
      [&] {
        sensor_msgs::Image image;
        image.header.stamp = ros::Time::now();
        image.height = image.width = 8;
        image.encoding = "mono8";
        image.step = 8;
        image.data.assign(64, 128);
        right.publish(image);
        std_msgs::String text;
        text.data = "not an image";
        wrong.publish(text);
        read();
        return levels.count("Right type") && levels["Right type"] == 0 && levels.count("Grid") && levels["Grid"] == 0 &&
               levels.count("Missing class") && levels.count("Wrong type");
      },
      60.0);
  EXPECT_TRUE(settled) << "no report with Grid and Right type Ok within 60 s";
  ros::WallDuration(3.0).sleep();  // the wrong type has had time to arrive, were it accepted
  read();
  for (const auto& [name, level] : levels)
    ROS_INFO("display '%s': level %d", name.c_str(), level);
  ASSERT_EQ(levels.count("Missing class"), 1u);
  ASSERT_EQ(levels.count("Wrong type"), 1u);
  EXPECT_EQ(levels["Missing class"], diagnostic_msgs::DiagnosticStatus::ERROR);
  EXPECT_NE(levels["Wrong type"], diagnostic_msgs::DiagnosticStatus::OK);
  EXPECT_EQ(levels["Right type"], diagnostic_msgs::DiagnosticStatus::OK);
  EXPECT_EQ(levels["Grid"], diagnostic_msgs::DiagnosticStatus::OK);
  EXPECT_EQ(levels.count("Global Status"), 1u);
  EXPECT_TRUE(rviz.running()) << "rviz exited";
}

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "test_rviz_display_status", 2).run();
}
