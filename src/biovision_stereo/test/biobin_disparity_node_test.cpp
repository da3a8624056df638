// Integration test: a textured fronto-parallel plane at disparity 8 through biobin_disparity, and the
// upstream stereo_image_proc point_cloud2 nodelet turning our DisparityImage into points.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>

#include <biovision_ros_common/rostest_helpers.hpp>
#include <cv_bridge/cv_bridge.h>
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <stereo_msgs/DisparityImage.h>

namespace
{
constexpr int kWidth = 320, kHeight = 240, kDisparity = 8;
constexpr double kFx = 300.0, kBaseline = 0.12;

class BioBinDisparityNodeTest : public ::testing::Test
{
public:
  BioBinDisparityNodeTest()
  {
    left_pub_ = nh_.advertise<sensor_msgs::Image>("stereo/left/image_rect_color", 2);
    right_pub_ = nh_.advertise<sensor_msgs::Image>("stereo/right/image_rect_color", 2);
    left_info_pub_ = nh_.advertise<sensor_msgs::CameraInfo>("stereo/left/camera_info", 2);
    right_info_pub_ = nh_.advertise<sensor_msgs::CameraInfo>("stereo/right/camera_info", 2);
    cv::RNG rng(5);
    cv::Mat small(kHeight / 4 + 2, (kWidth + 40) / 4 + 2, CV_8UC3);
    rng.fill(small, cv::RNG::UNIFORM, 0, 256);
    cv::resize(small, wide_, cv::Size(small.cols * 4, small.rows * 4), 0, 0, cv::INTER_CUBIC);
  }

  void onDisparity(const stereo_msgs::DisparityImageConstPtr& m)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    disparity_ = m;
  }
  void onPoints(const sensor_msgs::PointCloud2ConstPtr& m)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    points_ = m;
  }
  /// Raises `seen` on a disparity stamped at or after `from`: the output of frames published since then.
  ros::Subscriber watchDisparitiesFrom(const ros::Time& from, std::atomic<bool>& seen)
  {
    return nh_.subscribe<stereo_msgs::DisparityImage>("stereo/disparity", 10,
                                                      [from, &seen](const stereo_msgs::DisparityImageConstPtr& m) {
                                                        if (m->header.stamp >= from)
                                                          seen = true;
                                                      });
  }
  void onDiagnostics(const diagnostic_msgs::DiagnosticArrayConstPtr& m)
  {
    for (const auto& s : m->status)
      if (s.name.find("BioBin disparity") != std::string::npos && s.level == diagnostic_msgs::DiagnosticStatus::ERROR)
        saw_error_ = true;
  }

  sensor_msgs::CameraInfo info(const ros::Time& stamp, bool right, double fx = kFx) const
  {
    sensor_msgs::CameraInfo c;
    c.header.stamp = stamp;
    c.header.frame_id = "stereo_left_optical";
    c.width = kWidth;
    c.height = kHeight;
    c.distortion_model = "plumb_bob";
    c.D.assign(5, 0.0);
    c.K = {fx, 0, kWidth / 2.0, 0, fx, kHeight / 2.0, 0, 0, 1};
    c.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    c.P = {fx, 0, kWidth / 2.0, right ? -fx * kBaseline : 0.0, 0, fx, kHeight / 2.0, 0, 0, 0, 1, 0};
    return c;
  }

  void publishPair(double fx = kFx, const std::string& right_info_frame = "stereo_left_optical")
  {
    const ros::Time stamp = ros::Time::now();
    std_msgs::Header h;
    h.stamp = stamp;
    h.frame_id = "stereo_left_optical";
    // left(x) = wide(20 + x), right(x) = wide(20 + d + x): a plane at disparity d.
    const cv::Mat left = wide_(cv::Rect(20, 0, kWidth, kHeight)).clone();
    const cv::Mat right = wide_(cv::Rect(20 + kDisparity, 0, kWidth, kHeight)).clone();
    left_pub_.publish(cv_bridge::CvImage(h, "bgr8", left).toImageMsg());
    right_pub_.publish(cv_bridge::CvImage(h, "bgr8", right).toImageMsg());
    left_info_pub_.publish(info(stamp, false, fx));
    auto ri = info(stamp, true, fx + right_fx_offset_);
    ri.header.frame_id = right_info_frame;
    right_info_pub_.publish(ri);
  }

  template <typename Pred>
  bool publishUntil(Pred pred, double seconds, double fx = kFx,
                    const std::string& right_info_frame = "stereo_left_optical")
  {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
    while (ros::ok() && ros::WallTime::now() < end)
    {
      publishPair(fx, right_info_frame);
      ros::WallDuration(0.2).sleep();
      if (pred())
        return true;
    }
    return pred();
  }

  ros::NodeHandle nh_;
  ros::Publisher left_pub_, right_pub_, left_info_pub_, right_info_pub_;
  cv::Mat wide_;
  std::mutex mutex_;
  stereo_msgs::DisparityImageConstPtr disparity_;
  sensor_msgs::PointCloud2ConstPtr points_;
  std::atomic<bool> saw_error_{false};
  double right_fx_offset_ = 0.0;  ///< right camera_info's fx minus the left's
};

TEST_F(BioBinDisparityNodeTest, PlaneGivesItsDisparityAndPointCloud2ConsumesIt)
{
  ros::Subscriber ds = nh_.subscribe("stereo/disparity", 2, &BioBinDisparityNodeTest::onDisparity,
                                     static_cast<BioBinDisparityNodeTest*>(this));
  ros::Subscriber ps = nh_.subscribe("stereo/points2", 2, &BioBinDisparityNodeTest::onPoints,
                                     static_cast<BioBinDisparityNodeTest*>(this));
  ASSERT_TRUE(publishUntil(
      [&] {
        std::lock_guard<std::mutex> lock(mutex_);
        return disparity_ && points_;
      },
      60.0))
      << "disparity " << bool(disparity_) << ", points2 " << bool(points_);

  std::lock_guard<std::mutex> lock(mutex_);
  EXPECT_NEAR(disparity_->f, kFx, 1e-3);
  EXPECT_NEAR(disparity_->T, kBaseline, 1e-6);
  EXPECT_EQ(disparity_->image.encoding, "32FC1");
  EXPECT_EQ(disparity_->header.frame_id, "stereo_left_optical");
  const cv::Mat d = cv_bridge::toCvCopy(disparity_->image)->image;
  std::vector<float> valid;
  for (int y = 0; y < d.rows; ++y)
    for (int x = 0; x < d.cols; ++x)
      if (d.at<float>(y, x) >= disparity_->min_disparity)
        valid.push_back(d.at<float>(y, x));
  ASSERT_GT(valid.size(), 0.8 * d.total()) << "too few valid pixels";
  std::nth_element(valid.begin(), valid.begin() + valid.size() / 2, valid.end());
  EXPECT_NEAR(valid[valid.size() / 2], kDisparity, 0.25) << "median disparity";

  // point_cloud2 (upstream stereo_image_proc) reprojected our disparity: z = f T / d = 4.5 m.
  std::vector<float> z;
  for (sensor_msgs::PointCloud2ConstIterator<float> it(*points_, "z"); it != it.end(); ++it)
    if (std::isfinite(*it))
      z.push_back(*it);
  ASSERT_GT(z.size(), 0.5 * d.total()) << "point_cloud2 gave too few points";
  std::nth_element(z.begin(), z.begin() + z.size() / 2, z.end());
  EXPECT_NEAR(z[z.size() / 2], kFx * kBaseline / kDisparity, 0.15);
}

TEST_F(BioBinDisparityNodeTest, BadCameraInfoIsReportedAndTheNodeKeepsWorking)
{
  ros::Subscriber ds = nh_.subscribe("stereo/disparity", 2, &BioBinDisparityNodeTest::onDisparity,
                                     static_cast<BioBinDisparityNodeTest*>(this));
  ros::Subscriber diag = nh_.subscribe("/diagnostics", 20, &BioBinDisparityNodeTest::onDiagnostics,
                                       static_cast<BioBinDisparityNodeTest*>(this));
  // Zero focal length: nothing may be published from it, and an ERROR diagnostic must appear. Told apart
  // by stamp: the good frames the last test left queued or in progress may still come out meanwhile.
  const ros::Time bad_from = ros::Time::now();
  std::atomic<bool> from_bad{false};
  ros::Subscriber bad = watchDisparitiesFrom(bad_from, from_bad);
  EXPECT_TRUE(publishUntil([&] { return saw_error_.load(); }, 30.0, 0.0)) << "no ERROR diagnostic";
  ros::WallDuration(0.5).sleep();  // a frame still in progress would come out now
  EXPECT_FALSE(from_bad.load()) << "a disparity was published from a zero focal length";
  bad.shutdown();
  // Good input again: disparity comes back.
  EXPECT_TRUE(publishUntil(
      [&] {
        std::lock_guard<std::mutex> lock(mutex_);
        return bool(disparity_);
      },
      30.0));
  // The right camera_info in its own frame (image_geometry would abort on it): still disparity.
  {
    std::lock_guard<std::mutex> lock(mutex_);
    disparity_.reset();
  }
  EXPECT_TRUE(publishUntil(
      [&] {
        std::lock_guard<std::mutex> lock(mutex_);
        return bool(disparity_);
      },
      30.0, kFx, "stereo_right_optical"))
      << "no disparity when the right camera_info uses its own frame";
}
TEST_F(BioBinDisparityNodeTest, LeftAndRightFocalLengthsThatDifferAreRefusedWithoutAborting)
{
  // image_geometry's StereoCameraModel asserts left fx == right fx (also fy, cy): the node must refuse the
  // pair with an ERROR naming it, not abort, and match again once the pair is consistent.
  ros::Subscriber ds = nh_.subscribe("stereo/disparity", 2, &BioBinDisparityNodeTest::onDisparity,
                                     static_cast<BioBinDisparityNodeTest*>(this));
  std::atomic<bool> named{false};
  ros::Subscriber diag = nh_.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 20, [&](const diagnostic_msgs::DiagnosticArrayConstPtr& m) {
        for (const auto& s : m->status)
          if (s.name.find("BioBin disparity") != std::string::npos &&
              s.level == diagnostic_msgs::DiagnosticStatus::ERROR &&
              s.message.find("not a rectified pair") != std::string::npos)
            named = true;
      });
  ASSERT_TRUE(publishUntil(
      [&] {
        std::lock_guard<std::mutex> lock(mutex_);
        return bool(disparity_);
      },
      60.0))
      << "no disparity from a good pair";
  {
    std::lock_guard<std::mutex> lock(mutex_);
    disparity_.reset();
  }
  // Told apart by stamp: a good pair still in progress may come out after the switch (a CI run saw it).
  const ros::Time bad_from = ros::Time::now();
  std::atomic<bool> from_bad{false};
  ros::Subscriber bad = watchDisparitiesFrom(bad_from, from_bad);
  right_fx_offset_ = 1.0;
  EXPECT_TRUE(publishUntil([&] { return named.load(); }, 30.0)) << "no ERROR naming the inconsistent pair";
  ros::WallDuration(0.5).sleep();  // a frame still in progress would come out now
  EXPECT_FALSE(from_bad.load()) << "a disparity was published from an inconsistent pair";
  bad.shutdown();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    disparity_.reset();
  }
  right_fx_offset_ = 0.0;
  EXPECT_TRUE(publishUntil(
      [&] {
        std::lock_guard<std::mutex> lock(mutex_);
        return bool(disparity_);
      },
      30.0))
      << "no disparity after the inconsistent pair: did the node abort?";
}
}  // namespace

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "biobin_disparity_node_test", 2).run();
}
