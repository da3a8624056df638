// Saliency metrics on hand-made maps, and the .flo reader on hand-written files.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "biovision_common/eval/middlebury_flow.hpp"
#include "biovision_common/eval/saliency_metrics.hpp"

using namespace biovision_common;

namespace
{
cv::Mat blob(cv::Size s, cv::Point c, double sigma)
{
  cv::Mat m(s, CV_32F);
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x)
      m.at<float>(y, x) = static_cast<float>(
          std::exp(-((x - c.x) * (x - c.x) + (y - c.y) * (y - c.y)) / (2 * sigma * sigma)));
  return m;
}
}  // namespace

TEST(SaliencyMetrics, IdenticalMapsAreBest)
{
  const cv::Mat fix = blob({80, 60}, {40, 30}, 6);
  const SaliencyMetrics same = SaliencyMetrics::compute(fix * 3.0, fix);  // scale does not matter
  EXPECT_NEAR(same.cc, 1.0, 1e-5);
  EXPECT_NEAR(same.sim, 1.0, 1e-4);
  EXPECT_NEAR(same.kl, 0.0, 1e-4);
  EXPECT_GT(same.nss, 2.0);
  const SaliencyMetrics wrong = SaliencyMetrics::compute(blob({80, 60}, {10, 10}, 6), fix);
  EXPECT_LT(wrong.cc, 0.0);
  EXPECT_LT(wrong.sim, 0.2);
  EXPECT_GT(wrong.kl, 1.0);
  EXPECT_LT(wrong.nss, 0.0);
  // A flat map carries no information: CC and NSS 0.
  const SaliencyMetrics flat = SaliencyMetrics::compute(cv::Mat(60, 80, CV_32F, cv::Scalar(1)), fix);
  EXPECT_EQ(flat.cc, 0.0);
  EXPECT_EQ(flat.nss, 0.0);
}

TEST(SaliencyMetrics, PeaksAreTheLocalMaxima)
{
  cv::Mat fix = blob({100, 60}, {20, 30}, 4) + 0.6 * blob({100, 60}, {75, 30}, 4);
  const auto p = SaliencyMetrics::peaks(fix);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0], cv::Point(20, 30));
  EXPECT_EQ(p[1], cv::Point(75, 30));
}

TEST(MiddleburyFlow, ReadsHandWrittenFiles)
{
  const auto path = std::filesystem::temp_directory_path() / "biovision_flow_test.flo";
  {
    std::ofstream f(path, std::ios::binary);
    f.write("PIEH", 4);
    const std::int32_t w = 2, h = 1;
    f.write(reinterpret_cast<const char*>(&w), 4);
    f.write(reinterpret_cast<const char*>(&h), 4);
    const float v[4] = {1.5f, -2.f, 1e10f, 0.f};  // second pixel unknown
    f.write(reinterpret_cast<const char*>(v), sizeof v);
  }
  const cv::Mat flow = MiddleburyFlow::read(path.string());
  ASSERT_EQ(flow.size(), cv::Size(2, 1));
  EXPECT_EQ(flow.at<cv::Vec2f>(0, 0), cv::Vec2f(1.5f, -2.f));
  EXPECT_TRUE(std::isnan(flow.at<cv::Vec2f>(0, 1)[0]));
  {
    std::ofstream f(path, std::ios::binary);
    f.write("PIEH", 4);
    const std::int32_t w = 10, h = 10;
    f.write(reinterpret_cast<const char*>(&w), 4);
    f.write(reinterpret_cast<const char*>(&h), 4);
  }
  EXPECT_THROW(MiddleburyFlow::read(path.string()), std::runtime_error);  // truncated
  std::filesystem::remove(path);
  EXPECT_THROW(MiddleburyFlow::read(path.string()), std::runtime_error);  // missing
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
