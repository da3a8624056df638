// Integration test of the v1_cells node: lazy subscription, keypoints of a known image, survival of
// bad input with an ERROR diagnostic, and recovery afterwards; raw Bayer frames are read.
#include <cmath>
#include <memory>

#include <biovision_msgs/KeypointArray.h>
#include <cv_bridge/cv_bridge.h>
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>

#include "biovision_ros_common/rostest_helpers.hpp"

using biovision_ros_common::DiagnosticsWatch;
using biovision_ros_common::TopicProbe;
using biovision_ros_common::waitFor;

namespace
{
class V1CellsNodeTest : public ::testing::Test
{
public:
  void SetUp() override { image_pub_ = nh_.advertise<sensor_msgs::Image>("camera/image", 5); }

protected:
  // L-corner of a bright square on grey, 160x120, corner at (79.5, 59.5).
  static sensor_msgs::ImagePtr cornerImage(uint32_t seq)
  {
    cv::Mat img(120, 160, CV_8U, cv::Scalar(50));
    img(cv::Rect(80, 60, 80, 60)).setTo(200);
    std_msgs::Header h;
    h.seq = seq;
    h.stamp = ros::Time::now();
    h.frame_id = "stereo_left_optical";
    return cv_bridge::CvImage(h, "mono8", img).toImageMsg();
  }

  // Publishes the corner image until a keypoint array for it arrives.
  biovision_msgs::KeypointArrayConstPtr keypointsForCorner(TopicProbe<biovision_msgs::KeypointArray>& keypoints)
  {
    const size_t before = keypoints.count();
    uint32_t seq = 0;
    waitFor(
        [&] {
          image_pub_.publish(cornerImage(++seq));
          ros::WallDuration(0.1).sleep();
          return keypoints.count() > before;
        },
        30.0);
    return keypoints.count() > before ? keypoints.last() : nullptr;
  }

  static double distanceToCorner(const biovision_msgs::KeypointArray& kps)
  {
    double best = 1e9;
    for (const auto& k : kps.keypoints)
      best = std::min(best, std::hypot(k.x - 79.5, k.y - 59.5));
    return best;
  }

  ros::NodeHandle nh_;
  ros::Publisher image_pub_;
};

TEST_F(V1CellsNodeTest, LazySubscriptionKeypointsBadInputAndRecovery)
{
  // Nobody listens to keypoints yet: the node must not subscribe to the image.
  ros::WallDuration(1.0).sleep();
  EXPECT_EQ(image_pub_.getNumSubscribers(), 0u) << "v1_cells subscribed without listeners";

  auto keypoints = std::make_unique<TopicProbe<biovision_msgs::KeypointArray>>(nh_, "keypoints");
  DiagnosticsWatch diagnostics(nh_, "V1 cells");
  ASSERT_TRUE(waitFor([&] { return image_pub_.getNumSubscribers() > 0; }, 20.0)) << "v1_cells never subscribed";

  auto kps = keypointsForCorner(*keypoints);
  ASSERT_TRUE(kps) << "no keypoints message";
  EXPECT_EQ(kps->header.frame_id, "stereo_left_optical");
  EXPECT_EQ(kps->image_width, 160u);
  EXPECT_EQ(kps->image_height, 120u);
  EXPECT_LE(distanceToCorner(*kps), 2.0) << kps->keypoints.size() << " keypoints, none at the corner";

  // Bad input: a 4x4 image (below the model's smallest side), an image whose data is shorter than its
  // header says, an unknown encoding.
  std_msgs::Header h;
  h.stamp = ros::Time::now();
  image_pub_.publish(cv_bridge::CvImage(h, "mono8", cv::Mat(4, 4, CV_8U, cv::Scalar(9))).toImageMsg());
  sensor_msgs::Image truncated;
  truncated.header = h;
  truncated.width = 64;
  truncated.height = 64;
  truncated.encoding = "mono8";
  truncated.step = 64;
  truncated.data.resize(100);
  image_pub_.publish(truncated);
  truncated.encoding = "jpeg";
  truncated.data.resize(64 * 64);
  image_pub_.publish(truncated);
  EXPECT_TRUE(waitFor([&] { return diagnostics.sawError(); }, 15.0)) << "no ERROR diagnostic after bad input";

  // Still alive and correct.
  kps = keypointsForCorner(*keypoints);
  ASSERT_TRUE(kps) << "v1_cells stopped publishing after bad input";
  EXPECT_LE(distanceToCorner(*kps), 2.0);

  // A raw Bayer frame is demosaiced by the shared conversion, not refused.
  const size_t before = keypoints->count();
  cv::Mat raw(120, 160, CV_8U, cv::Scalar(50));
  raw(cv::Rect(80, 60, 80, 60)).setTo(200);
  image_pub_.publish(cv_bridge::CvImage(h, "bayer_rggb8", raw).toImageMsg());
  EXPECT_TRUE(keypoints->waitForCount(before + 1, 10.0)) << "no keypoints for a bayer_rggb8 frame";

  // Unsubscribing makes it drop the image subscription again.
  keypoints.reset();
  EXPECT_TRUE(waitFor([&] { return image_pub_.getNumSubscribers() == 0; }, 20.0));
}
}  // namespace

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "v1_cells_node_test", 2).run();
}
