#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "biovision_memory/landmark_corrector.hpp"

using namespace biovision_memory;

TEST(LandmarkCorrector, AKnownOffsetIsRecoveredFromSpreadLandmarks)
{
  LandmarkCorrectorParameters p;
  p.gain = 1.0;
  LandmarkCorrector c(p);
  const Pose2D truth{0.4, -0.3, 0.1};  // map_from_odom
  const std::vector<Eigen::Vector2d> landmarks{{2, 0}, {0, 2}, {-1, -1}};
  for (int i = 0; i < 3; ++i)
    ASSERT_TRUE(c.observe(landmarks[i], truth.inverse().apply(landmarks[i]), i));
  EXPECT_NEAR(c.mapFromOdom().x, truth.x, 1e-9);
  EXPECT_NEAR(c.mapFromOdom().y, truth.y, 1e-9);
  EXPECT_NEAR(c.mapFromOdom().yaw, truth.yaw, 1e-9);
}

TEST(LandmarkCorrector, OneLandmarkCorrectsTheTranslationOnlyAndOutliersAreIgnored)
{
  LandmarkCorrectorParameters p;
  p.gain = 1.0;
  LandmarkCorrector c(p);
  ASSERT_TRUE(c.observe({2, 0}, {1.7, 0.2}, 0));
  EXPECT_NEAR(c.mapFromOdom().x, 0.3, 1e-9);
  EXPECT_NEAR(c.mapFromOdom().y, -0.2, 1e-9);
  EXPECT_EQ(c.mapFromOdom().yaw, 0.0);
  EXPECT_FALSE(c.observe({2, 0}, {-3.0, 0.0}, 1));  // a 5 m jump: a mis-recognition
  EXPECT_FALSE(c.observe({NAN, 0}, {1, 0}, 1));
  // Deeper than max_depth (3.5 m) or a negative depth: not used, the estimate stays.
  EXPECT_FALSE(c.observe({2, 0}, {1.5, 0.0}, 2, 3.6));
  EXPECT_FALSE(c.observe({2, 0}, {1.5, 0.0}, 2, -1.0));
  EXPECT_NEAR(c.mapFromOdom().x, 0.3, 1e-9);
  EXPECT_EQ(c.sightings(), 1u);
  EXPECT_TRUE(c.observe({2, 0}, {1.7, 0.2}, 3, 3.4));
  EXPECT_EQ(c.sightings(), 2u);
  p.max_depth = 0.0;
  EXPECT_THROW(p.validate(), std::invalid_argument);
}

// One landmark (the demo's target, its only object) seen 30 times from 5 m with 0.3 m of stereo noise and its
// remembered position refined by a centimetre each time: the heading is not observable and must not move.
TEST(LandmarkCorrector, OneLandmarkSeenWithNoiseNeverTurnsTheMap)
{
  LandmarkCorrector c;
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.3);
  Eigen::Vector2d remembered(9.0, 1.8);
  for (int i = 0; i < 30; ++i)
  {
    remembered += Eigen::Vector2d(0.01 * noise(rng), 0.01 * noise(rng));
    c.observe(remembered, Eigen::Vector2d(9.0 + noise(rng), 1.8 + noise(rng)), 0.5 * i);
    ASSERT_EQ(c.mapFromOdom().yaw, 0.0) << "sighting " << i;
  }
  EXPECT_LT(std::hypot(c.mapFromOdom().x, c.mapFromOdom().y), 0.5);
}

// A base drives three 4 × 3 m loops with odometry that over-reads distance by 3 % and turns 1.5° per
// metre too far; four landmarks (already fixed in the map) are seen when within 3 m and ±30° of the heading
// with 5 cm noise. The final map → base_link error with correction must be at most half the error of
// raw odometry.
TEST(LandmarkCorrector, HalvesTheFinalPoseErrorOnASyntheticDrift)
{
  const std::vector<Eigen::Vector2d> landmarks{{5.0, -1.0}, {5.0, 4.0}, {-1.0, 4.0}, {-1.0, -1.0}};
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  LandmarkCorrector corrector;
  Pose2D truth, odom;
  const double dt = 0.1, v = 0.4;
  double t = 0.0, worst_raw = 0.0;
  for (int loop = 0; loop < 3; ++loop)
    for (double side : {4.0, 3.0, 4.0, 3.0})
    {
      for (double d = 0.0; d < side; d += v * dt)
      {
        const Pose2D step{v * dt, 0.0, 0.0};
        truth = truth.compose(step);
        odom = odom.compose(Pose2D{1.03 * v * dt, 0.0, 0.026 * v * dt});
        t += dt;
        for (const auto& l : landmarks)
        {
          const Eigen::Vector2d in_base = truth.inverse().apply(l) + Eigen::Vector2d(noise(rng), noise(rng));
          if (in_base.norm() > 3.0 || std::abs(std::atan2(in_base.y(), in_base.x())) > 0.52)
            continue;
          corrector.observe(l, odom.apply(in_base), t);
        }
      }
      for (int i = 0; i < 16; ++i)  // turn 90° left in place
      {
        truth = truth.compose(Pose2D{0, 0, M_PI / 32});
        odom = odom.compose(Pose2D{0, 0, 1.02 * M_PI / 32});
        t += dt;
      }
      worst_raw = std::max(worst_raw, std::hypot(odom.x - truth.x, odom.y - truth.y));
    }
  const double raw = std::hypot(odom.x - truth.x, odom.y - truth.y);
  const Pose2D corrected = corrector.mapFromOdom().compose(odom);
  const double fixed = std::hypot(corrected.x - truth.x, corrected.y - truth.y);
  RecordProperty("raw_error_m", std::to_string(raw));
  RecordProperty("corrected_error_m", std::to_string(fixed));
  EXPECT_GT(raw, 0.3) << "the drift must be large enough to matter";
  EXPECT_LE(fixed, 0.5 * raw) << "raw " << raw << " m, corrected " << fixed << " m";
  EXPECT_LT(std::abs(Pose2D::normalizeAngle(corrected.yaw - truth.yaw)),
            0.5 * std::abs(Pose2D::normalizeAngle(odom.yaw - truth.yaw)));
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
