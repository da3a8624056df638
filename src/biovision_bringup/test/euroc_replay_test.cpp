// The real EuRoC stereo pairs (../shared/data/stereo/euroc-v1_01-micro) are turned into a bag by
// euroc_to_bag, played into the upstream rectify nodelets, and the rectified pairs must be row-aligned:
// ORB matches between left and right differ in row by less than a pixel (they do not before).
#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>

#include <biovision_ros_common/rostest_helpers.hpp>
#include <cv_bridge/cv_bridge.h>
#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>

namespace
{
double medianRowOffset(const cv::Mat& left, const cv::Mat& right, int* matches_used)
{
  auto orb = cv::ORB::create(1500);
  std::vector<cv::KeyPoint> kl, kr;
  cv::Mat dl, dr;
  orb->detectAndCompute(left, cv::noArray(), kl, dl);
  orb->detectAndCompute(right, cv::noArray(), kr, dr);
  if (dl.empty() || dr.empty())
    return 1e9;
  cv::BFMatcher matcher(cv::NORM_HAMMING, true);
  std::vector<cv::DMatch> m;
  matcher.match(dl, dr, m);
  std::vector<double> dy;
  for (const auto& x : m)
  {
    const cv::Point2f a = kl[x.queryIdx].pt, b = kr[x.trainIdx].pt;
    // Plausible stereo matches only: right of the left point by less than 100 px, good descriptor.
    if (x.distance < 40 && a.x - b.x > -2 && a.x - b.x < 100 && std::abs(a.y - b.y) < 20)
      dy.push_back(std::abs(a.y - b.y));
  }
  *matches_used = static_cast<int>(dy.size());
  if (dy.empty())
    return 1e9;
  std::nth_element(dy.begin(), dy.begin() + dy.size() / 2, dy.end());
  return dy[dy.size() / 2];
}
}  // namespace

TEST(EurocReplay, RealPairsComeOutRectified)
{
  const char* env = std::getenv("BIOVISION_SHARED");
  const std::string dataset = std::string(env ? env : BIOVISION_DEFAULT_SHARED) + "/data/stereo/euroc-v1_01-micro/mav0";
  ASSERT_TRUE(std::filesystem::exists(dataset + "/cam0/sensor.yaml")) << dataset << " not found (set BIOVISION_SHARED)";
  const std::string bag = (std::filesystem::temp_directory_path() / "biovision_euroc_test.bag").string();
  const std::string convert = "rosrun biovision_sim euroc_to_bag --dataset '" + dataset + "' --output '" + bag + "'";
  ASSERT_EQ(std::system(convert.c_str()), 0) << convert;

  ros::NodeHandle nh;
  std::mutex mutex;
  std::map<uint64_t, cv::Mat> left_rect, right_rect, left_raw, right_raw;
  auto keep = [&](std::map<uint64_t, cv::Mat>& into) {
    return [&mutex, &into](const sensor_msgs::ImageConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex);
      into[m->header.stamp.toNSec()] = cv_bridge::toCvCopy(m, "mono8")->image;
    };
  };
  ros::Subscriber a = nh.subscribe<sensor_msgs::Image>("stereo/left/image_rect_color", 30, keep(left_rect));
  ros::Subscriber b = nh.subscribe<sensor_msgs::Image>("stereo/right/image_rect_color", 30, keep(right_rect));
  ros::Subscriber c = nh.subscribe<sensor_msgs::Image>("stereo/left/image_raw", 30, keep(left_raw));
  ros::Subscriber d = nh.subscribe<sensor_msgs::Image>("stereo/right/image_raw", 30, keep(right_raw));
  ros::WallDuration(2.0).sleep();  // let the rectify nodelets subscribe
  const std::string play = "rosbag play --quiet --rate=2 '" + bag + "'";
  ASSERT_EQ(std::system(play.c_str()), 0);
  ros::WallDuration(1.0).sleep();

  std::lock_guard<std::mutex> lock(mutex);
  EXPECT_GE(left_rect.size(), 15u) << "rectified left images";
  int pairs = 0;
  double worst_rect = 0, sum_raw = 0;
  for (const auto& [stamp, l] : left_rect)
  {
    if (!right_rect.count(stamp) || !left_raw.count(stamp) || !right_raw.count(stamp))
      continue;
    int used = 0, used_raw = 0;
    const double rect = medianRowOffset(l, right_rect.at(stamp), &used);
    const double raw = medianRowOffset(left_raw.at(stamp), right_raw.at(stamp), &used_raw);
    ASSERT_GT(used, 20) << "too few matches to judge";
    worst_rect = std::max(worst_rect, rect);
    sum_raw += raw;
    ++pairs;
  }
  ASSERT_GE(pairs, 10);
  EXPECT_LT(worst_rect, 1.0) << "rectified pairs are not row-aligned";
  std::printf("EuRoC: %d pairs, worst median row offset after rectification %.2f px, mean before %.2f px\n", pairs,
              worst_rect, sum_raw / pairs);
  std::filesystem::remove(bag);
}

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "euroc_replay_test", 2).run();
}
