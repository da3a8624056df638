#include <gtest/gtest.h>

#include <vector>

#include <opencv2/imgproc.hpp>

#include "correspondence_data.hpp"
#include "biovision_common/eval/roc_metrics.hpp"

using biovision_common::fpr95;
using biovision_common::fpr95AtThreshold;
using biovision_common::rocArea;

using namespace biovision_recognition;

TEST(RocMetrics, WithoutTiesBothReadingsAgree)
{
  std::vector<float> pos;
  for (int i = 1; i <= 20; ++i)
    pos.push_back(static_cast<float>(i));  // 95% recall: 19 of 20, threshold 19
  const std::vector<float> neg{0.5f, 10.5f, 18.5f, 19.5f, 25.f, 30.f, 40.f, 50.f};
  EXPECT_DOUBLE_EQ(fpr95AtThreshold(pos, neg), 3.0 / 8.0);
  EXPECT_DOUBLE_EQ(fpr95(pos, neg), 3.0 / 8.0);
}

TEST(RocMetrics, ATieAtTheThresholdIsSharedInProportion)
{
  // Every positive at distance 5: 95% recall takes 19 of the 20 tied positives, and with them the same
  // share of the 10 negatives tied at 5; the other 10 negatives are farther.
  const std::vector<float> pos(20, 5.f);
  std::vector<float> neg(10, 5.f);
  neg.insert(neg.end(), 10, 9.f);
  EXPECT_DOUBLE_EQ(fpr95AtThreshold(pos, neg), 0.5);
  EXPECT_DOUBLE_EQ(fpr95(pos, neg), 0.95 * 10 / 20);
  // Part of the positives below the tie: 15 at 1, 5 at 5 -> 4 of the 5 tied are needed (0.8 of the tie).
  std::vector<float> mixed(15, 1.f);
  mixed.insert(mixed.end(), 5, 5.f);
  EXPECT_DOUBLE_EQ(fpr95(mixed, neg), 0.8 * 10 / 20);
}

TEST(RocMetrics, RocAreaCountsTiesHalf)
{
  EXPECT_DOUBLE_EQ(rocArea({1.f, 1.f}, {2.f, 3.f}), 1.0);
  EXPECT_DOUBLE_EQ(rocArea({2.f}, {2.f}), 0.5);
  EXPECT_DOUBLE_EQ(rocArea({3.f}, {1.f, 2.f}), 0.0);
  EXPECT_DOUBLE_EQ(fpr95({}, {1.f}), 1.0);  // nothing to measure: the worst figure
}

TEST(SyntheticViewpoints, TheHomographyMapsImageContentToWhereTheWarpPutsIt)
{
  // A bright blob off centre: in every warped copy it must appear where the returned homography says,
  // to 0.1 px (a slip in the twice-size rendering's pixel-centre convention moves it by 0.25 px).
  cv::Mat image(160, 200, CV_8UC3, cv::Scalar::all(0));
  cv::circle(image, cv::Point(60, 50), 3, cv::Scalar::all(255), cv::FILLED);
  cv::GaussianBlur(image, image, cv::Size(), 2.0);
  std::vector<CorrespondencePair> pairs(1);
  pairs[0].name = "blob";
  pairs[0].a = image;
  pairs[0].b = image;  // the same image: warped once, not twice
  const auto warps = syntheticViewpoints(pairs, 4, 2.5, 3);
  ASSERT_EQ(warps.size(), 4u);
  for (const auto& w : warps)
  {
    ASSERT_EQ(w.b.size(), image.size());
    const cv::Matx33d h(w.homography.ptr<double>());
    const cv::Vec3d p = h * cv::Vec3d(60, 50, 1);
    cv::Mat gray;
    cv::cvtColor(w.b, gray, cv::COLOR_BGR2GRAY);
    cv::Mat weights;
    gray.convertTo(weights, CV_64F);
    const cv::Moments m = cv::moments(weights);
    EXPECT_NEAR(m.m10 / m.m00, p[0] / p[2], 0.1) << w.name;
    EXPECT_NEAR(m.m01 / m.m00, p[1] / p[2], 0.1) << w.name;
    // Not the identity: the blob moved or the view was compressed.
    EXPECT_GT(cv::norm(cv::Matx33d::eye() - h), 1e-3) << w.name;
  }
}
