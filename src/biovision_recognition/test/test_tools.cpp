#include <gtest/gtest.h>

#include <vector>

#include <opencv2/imgproc.hpp>

#include "correspondence_data.hpp"
#include "biovision_common/eval/roc_metrics.hpp"

using biovision_common::fpr95;
using biovision_common::fpr95AtThreshold;
using biovision_common::rocArea;
using biovision_common::shareWithin;

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

TEST(RocMetrics, ShareWithinARadiusIncludesTheRadius)
{
  // A radius matcher accepts d <= r: the recall / false-positive rate descriptor_eval --radii reports.
  const std::vector<float> distances{0.f, 10.f, 24.f, 24.f, 25.f, 60.f, 90.f, 128.f};
  EXPECT_DOUBLE_EQ(shareWithin(distances, 23.f), 2.0 / 8.0);
  EXPECT_DOUBLE_EQ(shareWithin(distances, 24.f), 4.0 / 8.0);
  EXPECT_DOUBLE_EQ(shareWithin(distances, 128.f), 1.0);
  EXPECT_DOUBLE_EQ(shareWithin({}, 24.f), 0.0);
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

TEST(SyntheticPair, RecordsTheViewChangeItMade)
{
  // The recorded tilt and scale are the singular values of the homography's Jacobian at the image centre
  // (the perspective term vanishes there), so an evaluation pooling by them pools what was really done.
  cv::Mat image(120, 160, CV_8UC3);
  cv::randu(image, cv::Scalar::all(0), cv::Scalar::all(255));
  std::mt19937 rng(7);
  int blurred = 0;
  for (int k = 0; k < 20; ++k)
  {
    const CorrespondencePair p = syntheticPair(image, "random", 4.0, true, rng);
    ASSERT_TRUE(p.synthetic.has_value());
    const cv::Matx33d h(p.homography.ptr<double>());
    const cv::Point2d c((image.cols - 1) / 2.0, (image.rows - 1) / 2.0);
    const double w = h(2, 0) * c.x + h(2, 1) * c.y + h(2, 2);
    const cv::Vec2d y((h(0, 0) * c.x + h(0, 1) * c.y + h(0, 2)) / w, (h(1, 0) * c.x + h(1, 1) * c.y + h(1, 2)) / w);
    const cv::Matx22d jacobian((h(0, 0) - y[0] * h(2, 0)) / w, (h(0, 1) - y[0] * h(2, 1)) / w,
                               (h(1, 0) - y[1] * h(2, 0)) / w, (h(1, 1) - y[1] * h(2, 1)) / w);
    cv::Mat singular;
    cv::SVD::compute(cv::Mat(jacobian), singular, cv::SVD::NO_UV);
    const double s1 = singular.at<double>(0), s2 = singular.at<double>(1);
    EXPECT_NEAR(p.synthetic->tilt, s1 / s2, 1e-6);
    EXPECT_NEAR(p.synthetic->scale, s1, 1e-6);
    EXPECT_GE(p.synthetic->tilt, 1.0);
    EXPECT_LE(p.synthetic->tilt, 4.0);
    if (p.synthetic->blur_sigma > 0)
    {
      ++blurred;
      EXPECT_GE(p.synthetic->blur_sigma, 0.5);
      EXPECT_LE(p.synthetic->blur_sigma, 2.0);
    }
  }
  EXPECT_GT(blurred, 0);
  EXPECT_LT(blurred, 20);
  std::mt19937 again(7);
  EXPECT_FALSE(syntheticPair(image, "plain", 4.0, false, again).synthetic->blur_sigma > 0);
}

TEST(DescriptorSplit, FitAndValidationPartitionTheDevSourcesAndNeverTouchTheHeldOutOnes)
{
  // The Middlebury scenes and a range of made-up collection sources: every source in exactly one of
  // heldout, fit, validation; dev = fit + validation; "all" takes every source.
  std::vector<std::string> sources{"Aloe",  "Art",   "Baby1",  "Baby2", "Bowling1",   "Cones",
                                   "Teddy", "Venus", "Rocks2", "Wood1", "Flowerpots", "RubberWhale"};
  for (int i = 0; i < 400; ++i)
    sources.push_back("source_" + std::to_string(i));
  int counts[3] = {0, 0, 0};
  for (const auto& s : sources)
  {
    const bool heldout = inSourcePart(s, "heldout"), fit = inSourcePart(s, "fit");
    const bool validation = inSourcePart(s, "validation");
    EXPECT_EQ(1, heldout + fit + validation) << s;
    EXPECT_EQ(fit || validation, inSourcePart(s, "dev")) << s;
    EXPECT_TRUE(inSourcePart(s, "all"));
    ++counts[heldout ? 0 : (fit ? 1 : 2)];
  }
  EXPECT_TRUE(inSourcePart("aloe", "heldout"));  // forced: opencv-doc ships copies
  EXPECT_TRUE(inSourcePart("RubberWhale", "heldout"));
  // Half held out, a quarter of the rest for validation, within a generous binomial margin.
  const double n = static_cast<double>(sources.size());
  EXPECT_NEAR(counts[0] / n, 0.5, 0.08);
  EXPECT_NEAR(counts[2] / static_cast<double>(counts[1] + counts[2]), 1.0 / kValidationFolds, 0.08);
  EXPECT_THROW(inSourcePart("Art", "train"), std::invalid_argument);
  // The old name-order parts still alternate, whatever the source.
  EXPECT_TRUE(inPart(0, "train", "x"));
  EXPECT_TRUE(inPart(1, "test", "x"));
  EXPECT_FALSE(inPart(1, "train", "x"));
  EXPECT_EQ(collectionPart("fit", "dev"), "fit");
  EXPECT_EQ(collectionPart("train", "dev"), "dev");
}
