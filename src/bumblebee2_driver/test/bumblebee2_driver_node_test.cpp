// rostest: bumblebee2_driver nodes (real roscore) on the committed synthetic RAW16 frame, and one without
// a camera.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "biovision_ros_common/rostest_helpers.hpp"

using biovision_ros_common::DiagnosticsWatch;
using biovision_ros_common::TopicProbe;
using biovision_ros_common::waitFor;

namespace
{
std::vector<uint8_t> g_raw;  // the frame file, 64 × 48 × 2 bytes
}

TEST(Bumblebee2DriverNode, TheRaw16FrameIsSplitIntoLeftAndRightWithTheirCalibration)
{
  ros::NodeHandle nh;
  TopicProbe<sensor_msgs::Image> left(nh, "file/stereo/left/image_raw"), right(nh, "file/stereo/right/image_raw");
  TopicProbe<sensor_msgs::CameraInfo> left_info(nh, "file/stereo/left/camera_info"),
      right_info(nh, "file/stereo/right/camera_info");
  ASSERT_TRUE(waitFor([&] { return left.count() > 2 && right.count() > 2 && right_info.count() > 0; }, 15.0));
  const auto l = left.last(), r = right.last();
  EXPECT_EQ(l->encoding, "bayer_grbg8");
  EXPECT_EQ(l->width, 64u);
  EXPECT_EQ(l->height, 48u);
  EXPECT_EQ(l->header.frame_id, "stereo_left_optical");
  EXPECT_EQ(r->header.frame_id, "stereo_right_optical");
  ASSERT_EQ(l->data.size(), 64u * 48u);
  for (size_t i = 0; i < l->data.size(); ++i)
  {
    ASSERT_EQ(l->data[i], g_raw[2 * i]) << "left pixel " << i << " is not the even byte";
    ASSERT_EQ(r->data[i], g_raw[2 * i + 1]) << "right pixel " << i << " is not the odd byte";
  }
  const auto li = left_info.last(), ri = right_info.last();
  EXPECT_EQ(li->width, 64u);
  EXPECT_DOUBLE_EQ(li->K[0], 80.0);
  EXPECT_DOUBLE_EQ(li->K[2], 32.0);
  EXPECT_DOUBLE_EQ(li->D[0], 0.01);
  EXPECT_DOUBLE_EQ(ri->P[3], -9.6) << "right P[3] = -fx * baseline from the calibration file";
  EXPECT_EQ(li->header.stamp, l->header.stamp);
  EXPECT_EQ(li->header.frame_id, "stereo_left_optical");
  EXPECT_TRUE(waitFor([&] { return left.count() >= 10; }, 3.0)) << "about 10 Hz";
}

TEST(Bumblebee2DriverNode, SwapLeftRightAndDebayerGiveColourImagesTheOtherWayRound)
{
  ros::NodeHandle nh;
  TopicProbe<sensor_msgs::Image> left(nh, "swapped/stereo/left/image_raw");
  TopicProbe<sensor_msgs::CameraInfo> info(nh, "swapped/stereo/left/camera_info");
  ASSERT_TRUE(waitFor([&] { return left.count() > 0 && info.count() > 0; }, 15.0));
  const auto l = left.last();
  EXPECT_EQ(l->encoding, "bgr8");
  ASSERT_EQ(l->data.size(), 64u * 48u * 3u);
  // Pixel (row 2, column 3) is red in GRBG: the debayered red channel there is the odd (right) byte.
  const size_t pixel = 2 * 64 + 3;
  EXPECT_NEAR(l->data[3 * pixel + 2], g_raw[2 * pixel + 1], 1);
  EXPECT_GT(std::abs(int(l->data[3 * pixel + 2]) - int(g_raw[2 * pixel])), 5) << "not the even (left) byte";
  EXPECT_EQ(info.last()->width, 64u) << "uncalibrated camera_info still carries the size";
  EXPECT_DOUBLE_EQ(info.last()->K[0], 0.0);
}

TEST(Bumblebee2DriverNode, NoCameraIsADiagnosticsErrorAndTheNodeKeepsRetrying)
{
  ros::NodeHandle nh;
  DiagnosticsWatch diagnostics(nh, "bb_nocam: Bumblebee-2");  // not its rate status
  TopicProbe<sensor_msgs::Image> left(nh, "nocam/stereo/left/image_raw");
  ASSERT_TRUE(waitFor([&] { return diagnostics.received() >= 3; }, 15.0));
  EXPECT_TRUE(diagnostics.sawError());
  const std::string m = diagnostics.lastMessage();
  EXPECT_NE(m.find("no camera"), std::string::npos) << m;
  EXPECT_EQ(left.count(), 0u) << "nothing published without a camera";
}

TEST(Bumblebee2DriverNode, AFrameFileThatIsADirectoryIsAnErrorAndTheNodeKeepsRunning)
{
  // It threw std::ios_failure out of the capture thread and aborted the process.
  ros::NodeHandle nh;
  DiagnosticsWatch diagnostics(nh, "bb_dir: Bumblebee-2");
  TopicProbe<sensor_msgs::Image> left(nh, "dir/stereo/left/image_raw");
  ASSERT_TRUE(waitFor([&] { return diagnostics.received() >= 3; }, 15.0)) << "the node died";
  EXPECT_TRUE(diagnostics.sawError());
  const std::string m = diagnostics.lastMessage();
  EXPECT_NE(m.find("not a regular file"), std::string::npos) << m;
  EXPECT_EQ(left.count(), 0u);
}

int main(int argc, char** argv)
{
  biovision_ros_common::RosTestRun tests(argc, argv, "bumblebee2_driver_node_test", 2);
  std::string path;
  ros::NodeHandle("~").getParam("frame_file", path);
  std::ifstream in(path, std::ios::binary);
  g_raw.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (g_raw.size() != 64u * 48u * 2u)
  {
    ROS_FATAL("cannot read the frame file %s", path.c_str());
    return 1;
  }
  return tests.run();
}
