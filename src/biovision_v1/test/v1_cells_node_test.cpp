// Integration test of the v1_cells node: lazy subscription, keypoints of a known image, survival of
// bad input with an ERROR diagnostic, and recovery afterwards.
#include <atomic>
#include <cmath>
#include <mutex>

#include <biovision_msgs/KeypointArray.h>
#include <cv_bridge/cv_bridge.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>

namespace
{
class V1CellsNodeTest : public ::testing::Test
{
public:
  void SetUp() override
  {
    image_pub_ = nh_.advertise<sensor_msgs::Image>("camera/image", 5);
  }

  void onKeypoints(const biovision_msgs::KeypointArrayConstPtr& msg)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    last_ = msg;
    ++received_;
  }

  void onDiagnostics(const diagnostic_msgs::DiagnosticArrayConstPtr& msg)
  {
    for (const auto& s : msg->status)
      if (s.name.find("V1 cells") != std::string::npos && s.level == diagnostic_msgs::DiagnosticStatus::ERROR)
        saw_error_ = true;
  }

protected:
  template <typename Pred>
  bool waitFor(Pred pred, double seconds)
  {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
    while (ros::ok() && ros::WallTime::now() < end)
    {
      if (pred())
        return true;
      ros::WallDuration(0.02).sleep();
    }
    return pred();
  }

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
  biovision_msgs::KeypointArrayConstPtr keypointsForCorner()
  {
    const int before = received_;
    uint32_t seq = 0;
    waitFor([&] {
      image_pub_.publish(cornerImage(++seq));
      ros::WallDuration(0.1).sleep();
      return received_ > before;
    }, 30.0);
    std::lock_guard<std::mutex> lock(mutex_);
    return received_ > before ? last_ : nullptr;
  }

  ros::NodeHandle nh_;
  ros::Publisher image_pub_;
  std::mutex mutex_;
  biovision_msgs::KeypointArrayConstPtr last_;
  std::atomic<int> received_{0};
  std::atomic<bool> saw_error_{false};
};

TEST_F(V1CellsNodeTest, LazySubscriptionKeypointsBadInputAndRecovery)
{
  // Nobody listens to keypoints yet: the node must not subscribe to the image.
  ros::WallDuration(1.0).sleep();
  EXPECT_EQ(image_pub_.getNumSubscribers(), 0u) << "v1_cells subscribed without listeners";

  ros::Subscriber kp_sub = nh_.subscribe("keypoints", 5, &V1CellsNodeTest::onKeypoints, static_cast<V1CellsNodeTest*>(this));
  ros::Subscriber diag_sub = nh_.subscribe("/diagnostics", 20, &V1CellsNodeTest::onDiagnostics, static_cast<V1CellsNodeTest*>(this));
  ASSERT_TRUE(waitFor([&] { return image_pub_.getNumSubscribers() > 0; }, 20.0)) << "v1_cells never subscribed";

  auto kps = keypointsForCorner();
  ASSERT_TRUE(kps) << "no keypoints message";
  EXPECT_EQ(kps->header.frame_id, "stereo_left_optical");
  EXPECT_EQ(kps->image_width, 160u);
  EXPECT_EQ(kps->image_height, 120u);
  double best = 1e9;
  for (const auto& k : kps->keypoints)
    best = std::min(best, std::hypot(k.x - 79.5, k.y - 59.5));
  EXPECT_LE(best, 2.0) << kps->keypoints.size() << " keypoints, none at the corner";

  // Bad input: a 4x4 image, a Bayer image, an image whose data is shorter than its header says.
  std_msgs::Header h;
  h.stamp = ros::Time::now();
  image_pub_.publish(cv_bridge::CvImage(h, "mono8", cv::Mat(4, 4, CV_8U, cv::Scalar(9))).toImageMsg());
  image_pub_.publish(cv_bridge::CvImage(h, "bayer_rggb8", cv::Mat(64, 64, CV_8U, cv::Scalar(9))).toImageMsg());
  sensor_msgs::Image truncated;
  truncated.header = h;
  truncated.width = 64;
  truncated.height = 64;
  truncated.encoding = "mono8";
  truncated.step = 64;
  truncated.data.resize(100);
  image_pub_.publish(truncated);
  EXPECT_TRUE(waitFor([&] { return saw_error_.load(); }, 15.0)) << "no ERROR diagnostic after bad input";

  // Still alive and correct.
  kps = keypointsForCorner();
  ASSERT_TRUE(kps) << "v1_cells stopped publishing after bad input";
  best = 1e9;
  for (const auto& k : kps->keypoints)
    best = std::min(best, std::hypot(k.x - 79.5, k.y - 59.5));
  EXPECT_LE(best, 2.0);

  // Unsubscribing makes it drop the image subscription again.
  kp_sub.shutdown();
  EXPECT_TRUE(waitFor([&] { return image_pub_.getNumSubscribers() == 0; }, 20.0));
}
}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "v1_cells_node_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
