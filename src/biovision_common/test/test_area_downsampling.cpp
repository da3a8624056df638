#include <gtest/gtest.h>

#include <numeric>
#include <random>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "biovision_common/area_downsampling.hpp"

using biovision_common::AreaDownsampling;

namespace
{
cv::Mat randomImage(cv::Size size, int type, std::mt19937& rng)
{
  cv::Mat m(size, type);
  cv::theRNG().state = rng();
  if (CV_MAT_DEPTH(type) == CV_8U)
    cv::randu(m, cv::Scalar::all(0), cv::Scalar::all(256));
  else
    cv::randu(m, cv::Scalar::all(-1), cv::Scalar::all(1));
  return m;
}
}  // namespace

TEST(AreaDownsampling, TapsCoverEachOutputCellWithWeightsSummingToOne)
{
  for (const auto& [n_in, n_out] : std::vector<std::pair<int, int>>{{450, 113}, {375, 94}, {8, 8}, {9, 2}, {100, 71}})
  {
    const auto taps = AreaDownsampling::axisTaps(n_in, n_out);
    ASSERT_EQ(static_cast<int>(taps.size()), n_out);
    int last = 0;
    for (const auto& t : taps)
    {
      EXPECT_NEAR(std::accumulate(t.weights.begin(), t.weights.end(), 0.0), 1.0, 2e-3);
      EXPECT_GE(t.first, last - 1);  // consecutive cells share at most one (partly covered) pixel
      EXPECT_LE(t.first + static_cast<int>(t.weights.size()), n_in);
      last = t.first + static_cast<int>(t.weights.size());
    }
    EXPECT_EQ(last, n_in);  // the last cell reaches the end
  }
  // An integer factor: plain box means.
  for (const auto& t : AreaDownsampling::axisTaps(12, 3))
    EXPECT_EQ(t.weights, std::vector<float>(4, 0.25f));
}

TEST(AreaDownsampling, EqualsOpenCvInterAreaWithinOneRounding)
{
  std::mt19937 rng(5);
  const std::vector<std::pair<cv::Size, cv::Size>> sizes{{{450, 375}, {113, 94}}, {{450, 375}, {225, 188}},
                                                         {{384, 288}, {96, 72}},  {{434, 383}, {109, 96}},
                                                         {{37, 23}, {10, 7}},     {{40, 30}, {40, 30}},
                                                         {{101, 57}, {70, 41}}};
  for (const auto& [in, out] : sizes)
    for (const int type : {CV_8UC1, CV_8UC3, CV_8UC4, CV_32FC1, CV_32FC3})
    {
      const cv::Mat src = randomImage(in, type, rng);
      cv::Mat ours, theirs;
      AreaDownsampling(in, out).apply(src, ours);
      cv::resize(src, theirs, out, 0, 0, cv::INTER_AREA);
      ASSERT_EQ(ours.size(), out);
      ASSERT_EQ(ours.type(), type);
      cv::Mat diff;
      cv::absdiff(ours, theirs, diff);
      double worst = 0;
      cv::minMaxLoc(diff.reshape(1), nullptr, &worst);
      if (CV_MAT_DEPTH(type) == CV_8U)
      {
        EXPECT_LE(worst, 1.0) << in << " -> " << out << " type " << type;
        EXPECT_LE(cv::countNonZero(diff.reshape(1)), std::max<int>(2, diff.total() * diff.channels() / 100))
            << in << " -> " << out;
      }
      else
        EXPECT_LE(worst, 1e-5) << in << " -> " << out << " type " << type;
    }
}

TEST(AreaDownsampling, HalvingAnEightBitImageIsOpenCvsExactly)
{
  std::mt19937 rng(9);
  for (const int type : {CV_8UC1, CV_8UC3})
  {
    const cv::Mat src = randomImage(cv::Size(320, 240), type, rng);
    cv::Mat ours, theirs;
    AreaDownsampling(src.size(), cv::Size(160, 120)).apply(src, ours);
    cv::resize(src, theirs, cv::Size(160, 120), 0, 0, cv::INTER_AREA);
    EXPECT_EQ(cv::norm(ours, theirs, cv::NORM_INF), 0.0);
  }
}

TEST(AreaDownsampling, AConstantImageStaysConstant)
{
  const cv::Mat src(375, 450, CV_8UC3, cv::Scalar(7, 128, 255));
  cv::Mat dst;
  AreaDownsampling(src.size(), cv::Size(113, 94)).apply(src, dst);
  cv::Mat diff;
  cv::absdiff(dst, cv::Scalar(7, 128, 255), diff);
  EXPECT_EQ(cv::countNonZero(diff.reshape(1)), 0);
}

TEST(AreaDownsampling, RefusesEnlargementAndMismatchedInput)
{
  EXPECT_THROW(AreaDownsampling(cv::Size(10, 10), cv::Size(11, 5)), std::invalid_argument);
  EXPECT_THROW(AreaDownsampling(cv::Size(10, 10), cv::Size(0, 5)), std::invalid_argument);
  const AreaDownsampling down(cv::Size(10, 10), cv::Size(5, 5));
  cv::Mat dst;
  EXPECT_THROW(down.apply(cv::Mat(9, 10, CV_8UC1), dst), std::invalid_argument);
  EXPECT_THROW(down.apply(cv::Mat(10, 10, CV_16UC1), dst), std::invalid_argument);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
