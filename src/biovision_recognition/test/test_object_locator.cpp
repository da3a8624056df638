#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "biovision_recognition/object_locator.hpp"

using biovision_recognition::ObjectLocator;

namespace
{
// An image of 320x240 whose disparity is at half resolution (160x120): the target's box [100, 60, 80x80]
// (image px) holds the target at disparity 10; an occluder at disparity 30 covers the box's left 60%.
constexpr float kTarget = 10.f, kOccluder = 30.f;
const cv::Size kImage(320, 240);
const cv::Rect kBox(100, 60, 80, 80);

cv::Mat disparity()
{
  cv::Mat d(120, 160, CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  d(cv::Rect(50, 30, 40, 40)).setTo(kTarget);
  d(cv::Rect(50, 30, 24, 40)).setTo(kOccluder);
  return d;
}

ObjectLocator::Camera camera()
{
  ObjectLocator::Camera c;
  c.focal_length = 200.0;  // at the disparity's resolution
  c.baseline = 0.12;
  c.fx = c.fy = 200.0;
  c.cx = 80.0;
  c.cy = 60.0;
  c.min_disparity = 0.f;
  return c;
}
}  // namespace

TEST(ObjectLocator, TheDepthIsTheMatchesDisparityNotTheOccluderThatFillsMostOfTheBox)
{
  // Matches on the visible right part of the target (image x 150..178).
  const std::vector<cv::Point2f> matches{{152, 70}, {160, 90}, {170, 110}, {176, 130}};
  cv::Point3d p;
  ASSERT_EQ(ObjectLocator::locate(disparity(), camera(), kImage, kBox, matches, p), ObjectLocator::Source::Matches);
  EXPECT_NEAR(p.z, 200.0 * 0.12 / kTarget, 1e-9);
  // The box centre's ray: image (140, 100) is (70, 50) at the disparity's resolution.
  EXPECT_NEAR(p.x, (70.0 - 80.0) * p.z / 200.0, 1e-9);
  EXPECT_NEAR(p.y, (50.0 - 60.0) * p.z / 200.0, 1e-9);

  // Without matches, the box median: the occluder's depth (what the old position did).
  ASSERT_EQ(ObjectLocator::locate(disparity(), camera(), kImage, kBox, {}, p), ObjectLocator::Source::WholeBox);
  EXPECT_NEAR(p.z, 200.0 * 0.12 / kOccluder, 1e-9);
}

TEST(ObjectLocator, TooFewMatchesWithADisparityFallBackToTheBoxAndNoDataGivesNoPosition)
{
  cv::Point3d p(-1, -1, -1);
  // Two matches with a disparity and two in the invalid background: 2 < kMinMatchDisparities.
  const std::vector<cv::Point2f> matches{{152, 70}, {160, 90}, {10, 10}, {300, 230}};
  EXPECT_EQ(ObjectLocator::locate(disparity(), camera(), kImage, kBox, matches, p), ObjectLocator::Source::WholeBox);
  EXPECT_NEAR(p.z, 200.0 * 0.12 / kOccluder, 1e-9);

  // A match next to a hole still counts: its 3x3 neighbourhood has valid pixels.
  cv::Mat holes = disparity();
  holes.at<float>(35, 80) = std::numeric_limits<float>::infinity();
  const std::vector<cv::Point2f> near_hole{{160, 70}, {161, 71}, {170, 110}};
  EXPECT_EQ(ObjectLocator::locate(holes, camera(), kImage, kBox, near_hole, p), ObjectLocator::Source::Matches);
  EXPECT_NEAR(p.z, 200.0 * 0.12 / kTarget, 1e-9);

  // Nothing valid (all at or below min_disparity, or NaN): no position, p untouched.
  ObjectLocator::Camera c = camera();
  c.min_disparity = 40.f;
  p = cv::Point3d(-1, -1, -1);
  EXPECT_EQ(ObjectLocator::locate(disparity(), c, kImage, kBox, matches, p), ObjectLocator::Source::None);
  EXPECT_EQ(p, cv::Point3d(-1, -1, -1));
  EXPECT_EQ(ObjectLocator::locate(cv::Mat(0, 0, CV_32F), camera(), kImage, kBox, matches, p),
            ObjectLocator::Source::None);
  // A box outside the disparity and no matches: no position.
  EXPECT_EQ(ObjectLocator::locate(disparity(), camera(), kImage, cv::Rect(400, 300, 20, 20), {}, p),
            ObjectLocator::Source::None);
}

TEST(ObjectLocator, BadArgumentsThrow)
{
  cv::Point3d p;
  EXPECT_THROW(ObjectLocator::locate(cv::Mat(120, 160, CV_16S), camera(), kImage, kBox, {}, p), std::invalid_argument);
  EXPECT_THROW(ObjectLocator::locate(disparity(), camera(), cv::Size(), kBox, {}, p), std::invalid_argument);
  ObjectLocator::Camera c = camera();
  c.baseline = 0;
  EXPECT_THROW(ObjectLocator::locate(disparity(), c, kImage, kBox, {}, p), std::invalid_argument);
  c = camera();
  c.fy = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(ObjectLocator::locate(disparity(), c, kImage, kBox, {}, p), std::invalid_argument);
}
