// The head's attractor dynamics in a closed loop with a simulated servo and camera field of view.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "biovision_attractor/head_attractor.hpp"

using namespace biovision_attractor;

namespace
{
constexpr double kDt = 0.1;  // control period [s]
constexpr double kHalfFov = 21.5 * M_PI / 180;
constexpr double kServoSpeed = 3.0;  // [rad/s]

// Objects at fixed head-centred directions; those within the field of view are "seen".
std::vector<SeenRegion> look(const std::vector<double>& objects, double pan)
{
  std::vector<SeenRegion> seen;
  for (double o : objects)
    if (std::abs(o - pan) <= kHalfFov)
      seen.push_back({o, 0.0, 1.0, 1000.0});
  return seen;
}

double servo(double pan, double command)
{
  return pan + std::clamp(command - pan, -kServoSpeed * kDt, kServoSpeed * kDt);
}

double deg(double d)
{
  return d * M_PI / 180;
}
}  // namespace

TEST(HeadAttractor, OneSalientDirectionIsAStableFixedPoint)
{
  HeadAttractorParameters p;
  p.repulsion_step = 0.0;  // the attractor alone, no boredom
  HeadAttractor head(p);
  double pan = 0.0;
  const double object = deg(17);  // inside the view (+-21.5 deg) from 0 deg
  for (int k = 0; k < 600; ++k)
  {
    pan = servo(pan, head.update(look({object}, pan), pan, k * kDt, kDt, kHalfFov).command);
    if (k > 200)
    {
      ASSERT_NEAR(pan, object, deg(1)) << "left the attractor at t=" << k * kDt;
    }
  }
  // Perturbed (still in view), it comes back.
  pan += deg(15);
  for (int k = 0; k < 200; ++k)
    pan = servo(pan, head.update(look({object}, pan), pan, 60 + k * kDt, kDt, kHalfFov).command);
  EXPECT_NEAR(pan, object, deg(1));
}

TEST(HeadAttractor, TwoEqualTargetsAlternateWithBoundedDwell)
{
  HeadAttractor head{HeadAttractorParameters()};
  double pan = 0.0;
  // Both visible from straight ahead, never together from either of them.
  const std::vector<double> objects = {deg(-15), deg(15)};
  int side = 0, switches = 0;
  double since_switch = 0.0, longest_dwell = 0.0;
  for (int k = 0; k < 1800; ++k)  // 180 s
  {
    pan = servo(pan, head.update(look(objects, pan), pan, k * kDt, kDt, kHalfFov).command);
    const int now = pan > deg(10) ? 1 : (pan < deg(-10) ? -1 : 0);
    since_switch += kDt;
    if (now != 0 && now != side)
    {
      if (side != 0)
      {
        ++switches;
        longest_dwell = std::max(longest_dwell, since_switch);
      }
      side = now;
      since_switch = 0;
    }
  }
  EXPECT_GE(switches, 4) << "the head should alternate between the two targets";
  EXPECT_LT(longest_dwell, 40.0) << "dwell time must be bounded";
}

TEST(HeadAttractor, NeverBeyondTheLimitsUnderAnyInput)
{
  HeadAttractorParameters p;
  HeadAttractor head(p);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-4, 4), unit(0, 1);
  double pan = 0.0;
  for (int k = 0; k < 20000; ++k)
  {
    std::vector<SeenRegion> regions;
    const int n = static_cast<int>(unit(rng) * 5);
    for (int i = 0; i < n; ++i)
      regions.push_back({k % 211 == 0 ? NAN : angle(rng), 0.0, k % 97 == 0 ? NAN : unit(rng) * 3 - 1, 500.0});
    if (k % 1000 == 0)
    {
      static const HeadAttractor::Behaviour all[] = {HeadAttractor::Behaviour::kExplore,
                                                     HeadAttractor::Behaviour::kTrack,
                                                     HeadAttractor::Behaviour::kLookAhead,
                                                     HeadAttractor::Behaviour::kHold};
      head.setBehaviour(all[(k / 1000) % 4], angle(rng));
    }
    const double dt = k % 331 == 0 ? NAN : kDt * unit(rng) * 3;
    const auto out = head.update(regions, k % 503 == 0 ? NAN : pan, k * kDt, dt, kHalfFov);
    ASSERT_GE(out.command, p.pan_lower);
    ASSERT_LE(out.command, p.pan_upper);
    ASSERT_TRUE(std::isfinite(out.rate));
    ASSERT_LE(std::abs(out.rate), p.max_rate);
    pan = servo(pan, out.command);
  }
}

TEST(HeadAttractor, TrackingKeepsAMovingTargetCentred)
{
  HeadAttractor head{HeadAttractorParameters()};
  double pan = 0.0, worst = 0.0;
  for (int k = 0; k < 1200; ++k)
  {
    const double t = k * kDt;
    const double target = deg(50) * std::sin(0.15 * t);
    head.setBehaviour(HeadAttractor::Behaviour::kTrack, target);
    pan = servo(pan, head.update(look({target}, pan), pan, t, kDt, kHalfFov).command);
    if (t > 10)
      worst = std::max(worst, std::abs(pan - target));
  }
  // Sections are 20 deg wide: the target stays in view (half field of view 21.5 deg).
  EXPECT_LT(worst, kHalfFov);
}

TEST(HeadAttractor, LookAheadReturnsToStraightAheadPeriodically)
{
  HeadAttractorParameters p;
  HeadAttractor head(p);
  head.setBehaviour(HeadAttractor::Behaviour::kLookAhead);
  double pan = deg(60);
  std::vector<double> ahead_times;
  bool was_ahead = false;
  for (int k = 0; k < 600; ++k)
  {
    const double t = k * kDt;
    pan = servo(pan, head.update(look({deg(60)}, pan), pan, t, kDt, kHalfFov).command);
    const bool ahead = std::abs(pan) < deg(5);
    if (ahead && !was_ahead)
      ahead_times.push_back(t);
    was_ahead = ahead;
  }
  ASSERT_GE(ahead_times.size(), 5u);
  for (size_t i = 1; i < ahead_times.size(); ++i)
    EXPECT_NEAR(ahead_times[i] - ahead_times[i - 1], p.look_ahead_period, 1.0);
}

TEST(HeadAttractor, NothingSalientReturnsToSafeStraightAhead)
{
  HeadAttractorParameters p;
  HeadAttractor head(p);
  double pan = deg(70);
  for (int k = 0; k < 300; ++k)
    pan = servo(pan, head.update({}, pan, k * kDt, kDt, kHalfFov).command);
  EXPECT_LT(std::abs(pan), deg(12)) << "should settle straight ahead, not run away";
}

TEST(HeadAttractor, TiltFollowsTheFixatedTargetWithinItsLimits)
{
  HeadAttractorParameters p;
  p.repulsion_step = 0.0;
  HeadAttractor head(p);
  double pan = 0.0, tilt = p.default_tilt;
  const double object_pan = deg(10), object_tilt = deg(25);  // lower than the default tilt
  for (int k = 0; k < 400; ++k)
  {
    std::vector<SeenRegion> seen;
    if (std::abs(object_pan - pan) <= kHalfFov)
      seen.push_back({object_pan, object_tilt, 1.0, 1000.0});
    const auto out = head.update(seen, pan, k * kDt, kDt, kHalfFov, tilt);
    ASSERT_GE(out.tilt_command, p.tilt_lower);
    ASSERT_LE(out.tilt_command, p.tilt_upper);
    pan = servo(pan, out.command);
    tilt = servo(tilt, out.tilt_command);
  }
  EXPECT_NEAR(tilt, object_tilt, deg(1));
  // A target below the tilt limit: the command stops at the limit.
  HeadAttractor low(p);
  tilt = 0.0;
  for (int k = 0; k < 400; ++k)
  {
    const auto out = low.update({{0.0, 2.0, 1.0, 1000.0}}, 0.0, k * kDt, kDt, kHalfFov, tilt);
    ASSERT_LE(out.tilt_command, p.tilt_upper);
    tilt = servo(tilt, out.tilt_command);
  }
  EXPECT_NEAR(tilt, p.tilt_upper, 1e-9);
}

TEST(HeadAttractor, HoldKeepsThePan)
{
  HeadAttractor head{HeadAttractorParameters()};
  head.setBehaviour(HeadAttractor::Behaviour::kHold);
  const auto out = head.update(look({deg(40)}, deg(10)), deg(10), 0, kDt, kHalfFov);
  EXPECT_EQ(out.rate, 0.0);
  EXPECT_DOUBLE_EQ(out.command, deg(10));
}

TEST(HeadAttractorParameters, RejectsBadValues)
{
  HeadAttractorParameters p;
  p.sections = 2;
  EXPECT_THROW(p.validate(), std::invalid_argument);
  p = HeadAttractorParameters();
  p.pan_lower = 1;
  p.pan_upper = -1;
  EXPECT_THROW(HeadAttractor{p}, std::invalid_argument);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
