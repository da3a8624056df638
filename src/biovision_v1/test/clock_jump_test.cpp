// v1_cells under simulated time that jumps back (rosbag play -l, a restarted simulator): diagnostics keep
// being published about once a second and report the jump; keypoints keep coming for new frames.
#include <biovision_msgs/KeypointArray.h>
#include <cv_bridge/cv_bridge.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>

#include "biovision_ros_common/rostest_helpers.hpp"

using biovision_ros_common::DiagnosticsWatch;
using biovision_ros_common::TopicProbe;
using biovision_ros_common::waitFor;

namespace
{
class ClockJumpTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
    image_pub_ = nh_.advertise<sensor_msgs::Image>("camera/image", 5);
  }

  /// Runs simulated time from `start` for `wall_seconds`, 10 clock ticks and 5 frames per wall second.
  void runClock(double start, double wall_seconds)
  {
    const int ticks = static_cast<int>(wall_seconds * 10);
    for (int i = 0; i < ticks && ros::ok(); ++i)
    {
      rosgraph_msgs::Clock c;
      c.clock = ros::Time(start + 0.1 * i);
      clock_pub_.publish(c);
      if (i % 2 == 0)
        publishFrame(c.clock);
      ros::WallDuration(0.1).sleep();
    }
  }

  void publishFrame(const ros::Time& stamp)
  {
    cv::Mat img(120, 160, CV_8U, cv::Scalar(50));
    img(cv::Rect(80, 60, 80, 60)).setTo(200);
    std_msgs::Header h;
    h.stamp = stamp;
    image_pub_.publish(cv_bridge::CvImage(h, "mono8", img).toImageMsg());
  }

  ros::NodeHandle nh_;
  ros::Publisher clock_pub_, image_pub_;
};

TEST_F(ClockJumpTest, DiagnosticsAndOutputContinueAfterTimeJumpsBack)
{
  DiagnosticsWatch diagnostics(nh_, "V1 cells");
  TopicProbe<biovision_msgs::KeypointArray> keypoints(nh_, "keypoints");
  ASSERT_TRUE(waitFor([&] { return image_pub_.getNumSubscribers() > 0; }, 20.0)) << "v1_cells never subscribed";

  runClock(1000.0, 4.0);
  ASSERT_GE(diagnostics.received(), 2u) << "no diagnostics before the jump";
  const size_t frames_before = keypoints.count();
  ASSERT_GT(frames_before, 0u);

  diagnostics.clear();
  runClock(10.0, 5.0);  // the bag looped: 990 s back
  // Published on wall time: ~5 in 5 s. The stock updater would publish none until t = 1004 s.
  EXPECT_GE(diagnostics.received(), 3u) << "diagnostics stalled after the jump";
  EXPECT_NE(diagnostics.lastMessage().find("processing"), std::string::npos) << diagnostics.lastMessage();
  EXPECT_GT(keypoints.count(), frames_before) << "no keypoints for frames after the jump";
}
}  // namespace

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "test_v1_clock_jump", 2).run();
}
