// The forcelets of attractor dynamics (thesis §4.7, §5.4): signs (REP-103, + = left), zero crossings and
// their stability, symmetry, bounds; softmax weights, target selection, sectors; and the base heading
// controller of §5.4 built from them.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "biovision_attractor/forcelets.hpp"
#include "biovision_attractor/head_attractor_parameters.hpp"

using namespace biovision_attractor;

namespace
{
double deg(double d)
{
  return d * M_PI / 180;
}

// Angles from -pi to pi in 1e-3 rad steps around a forcelet at psi.
std::vector<double> sweep(double psi)
{
  std::vector<double> phis;
  for (double d = -M_PI; d <= M_PI; d += 1e-3)
    phis.push_back(psi + d);
  return phis;
}
}  // namespace

TEST(Forcelets, AttractionPullsTowardsItsDirectionFromBothSides)
{
  const double psi = deg(30), alpha = 50, weight = 0.7, epsilon = 10;
  EXPECT_EQ(attraction(psi, psi, alpha, weight, epsilon), 0.0);
  EXPECT_GT(attraction(psi - 0.1, psi, alpha, weight, epsilon), 0.0) << "right of the target: turn left";
  EXPECT_LT(attraction(psi + 0.1, psi, alpha, weight, epsilon), 0.0) << "left of the target: turn right";
  // Stable fixed point: negative slope at psi.
  const double h = 1e-6;
  EXPECT_LT(attraction(psi + h, psi, alpha, weight, epsilon) - attraction(psi - h, psi, alpha, weight, epsilon), 0.0);
  // The head's historical code: alpha * d * w * exp(-d^2 / eps), d = psi - phi.
  const double d = psi - 0.2;
  EXPECT_DOUBLE_EQ(attraction(0.2, psi, alpha, weight, epsilon), alpha * d * weight * std::exp(-d * d / epsilon));
  EXPECT_EQ(attraction(0.2, psi, alpha, 0.0, epsilon), 0.0) << "weight 0: no attraction";
}

TEST(Forcelets, AttractionAndRepulsionAreOddAboutTheirDirectionAndBounded)
{
  const double psi = deg(-20), alpha = 50, epsilon = 0.5;
  const double bound = alpha * std::sqrt(epsilon / 2) * std::exp(-0.5);
  double largest_a = 0, largest_r = 0, at_a = 0;
  for (double phi : sweep(psi))
  {
    const double d = phi - psi;
    EXPECT_NEAR(attraction(psi + d, psi, alpha, 1.0, epsilon), -attraction(psi - d, psi, alpha, 1.0, epsilon), 1e-12);
    EXPECT_NEAR(repulsion(psi + d, psi, alpha, 1.0, epsilon), -repulsion(psi - d, psi, alpha, 1.0, epsilon), 1e-12);
    const double a = std::abs(attraction(phi, psi, alpha, 1.0, epsilon));
    if (a > largest_a)
    {
      largest_a = a;
      at_a = std::abs(d);
    }
    largest_r = std::max(largest_r, std::abs(repulsion(phi, psi, alpha, 1.0, epsilon)));
  }
  EXPECT_LE(largest_a, bound + 1e-12);
  EXPECT_NEAR(largest_a, bound, 1e-4) << "the bound is reached";
  EXPECT_NEAR(at_a, std::sqrt(epsilon / 2), 2e-3) << "at |psi - phi| = sqrt(epsilon / 2)";
  EXPECT_LE(largest_r, bound + 1e-12);
  // Local: nothing left far away (6 sigma).
  EXPECT_LT(std::abs(attraction(psi + 3, psi, alpha, 1.0, epsilon)), 1e-6 * bound);
  EXPECT_LT(std::abs(repulsion(psi + 3, psi, alpha, 1.0, epsilon)), 1e-6 * bound);
}

TEST(Forcelets, RepulsionPushesAwayToTheSideItIsOn)
{
  const double psi = deg(10), alpha = 50, strength = 2.0, epsilon = 15;
  EXPECT_EQ(repulsion(psi, psi, alpha, strength, epsilon), 0.0);
  EXPECT_GT(repulsion(psi + 0.1, psi, alpha, strength, epsilon), 0.0) << "left of the repeller: further left";
  EXPECT_LT(repulsion(psi - 0.1, psi, alpha, strength, epsilon), 0.0) << "right of the repeller: further right";
  const double h = 1e-6;
  EXPECT_GT(repulsion(psi + h, psi, alpha, strength, epsilon) - repulsion(psi - h, psi, alpha, strength, epsilon), 0.0)
      << "an unstable fixed point";
  EXPECT_EQ(repulsion(psi + 0.1, psi, alpha, 0.0, epsilon), 0.0) << "strength 0: no repulsion";
  EXPECT_DOUBLE_EQ(repulsion(0.3, psi, alpha, strength, epsilon),
                   -repulsion(2 * psi - 0.3, psi, alpha, strength, epsilon));
}

TEST(Forcelets, SineAttractionHasOneStableAndOneUnstableZero)
{
  const double psi = deg(40), alpha = 1.0, h = 1e-6;
  EXPECT_NEAR(sineAttraction(psi, psi, alpha), 0.0, 1e-15);
  EXPECT_NEAR(sineAttraction(psi + M_PI, psi, alpha), 0.0, 1e-15);
  EXPECT_LT(sineAttraction(psi + h, psi, alpha) - sineAttraction(psi - h, psi, alpha), 0.0) << "stable at the goal";
  EXPECT_GT(sineAttraction(psi + M_PI + h, psi, alpha) - sineAttraction(psi + M_PI - h, psi, alpha), 0.0)
      << "unstable opposite the goal";
  EXPECT_GT(sineAttraction(psi - 1.0, psi, alpha), 0.0) << "goal to the left: turn left";
  EXPECT_LT(sineAttraction(psi + 1.0, psi, alpha), 0.0);
  for (double phi : sweep(psi))
  {
    ASSERT_LE(std::abs(sineAttraction(phi, psi, 2.5)), 2.5);
    ASSERT_NEAR(sineAttraction(phi + 2 * M_PI, psi, 2.5), sineAttraction(phi, psi, 2.5), 1e-12) << "periodic";
  }
  EXPECT_NEAR(std::abs(sineAttraction(psi + M_PI / 2, psi, 2.5)), 2.5, 1e-12);
}

TEST(Forcelets, RepulsionStrengthFallsWithTheLevel)
{
  const double beta = 0.5;
  EXPECT_EQ(repulsionStrength(1.0, beta), 0.0) << "level 1 = minimum repulsion = none";
  EXPECT_DOUBLE_EQ(repulsionStrength(0.0, beta), std::exp(1 / beta) - 1);
  double previous = -1;
  for (double level = 1.0; level >= 0.0; level -= 0.05)
  {
    const double s = repulsionStrength(level, beta);
    EXPECT_GT(s, previous);
    previous = s;
  }
}

TEST(Forcelets, WallsTurnBackNearTheEndsAndVanishMidField)
{
  const HeadAttractorParameters p;
  const double half_section = p.field / p.sections / 2;
  const double lower = p.pan_lower - half_section, upper = p.pan_upper + half_section;
  auto wall = [&](double phi) { return walls(phi, lower, upper, p.alpha_repulsion, p.beta_repulsion, p.wall_epsilon); };
  EXPECT_GT(wall(deg(-85)), 1.0) << "near the right end: turn left";
  EXPECT_LT(wall(deg(85)), -1.0) << "near the left end: turn right";
  EXPECT_NEAR(wall(deg(30)), -wall(deg(-30)), 1e-12) << "symmetric limits, antisymmetric walls";
  EXPECT_LT(std::abs(wall(0.0)), 1e-12);
  EXPECT_LT(std::abs(wall(deg(60))), 1e-3) << "nil at +-60 deg (README)";
  // The sum of the two repellers of maximum strength.
  const double s = repulsionStrength(0.0, p.beta_repulsion);
  EXPECT_DOUBLE_EQ(wall(1.3), repulsion(1.3, lower, p.alpha_repulsion, s, p.wall_epsilon) +
                                  repulsion(1.3, upper, p.alpha_repulsion, s, p.wall_epsilon));
}

TEST(Forcelets, SoftmaxWeightsNormaliseAndIgnoreWeakStrengths)
{
  const std::vector<double> a = {0.0, 0.02, 0.5, 0.9, 0.5};
  const std::vector<double> w = softmaxWeights(a, 0.05, 0.1);
  ASSERT_EQ(w.size(), a.size());
  EXPECT_EQ(w[0], 0.0);
  EXPECT_EQ(w[1], 0.0) << "below the threshold";
  EXPECT_NEAR(w[2] + w[3] + w[4], 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(w[2], w[4]);
  EXPECT_NEAR(w[3] / w[2], std::exp((0.9 - 0.5) / 0.1), 1e-9);
  for (double x : softmaxWeights({0.01, 0.0}, 0.05, 0.1))
    EXPECT_EQ(x, 0.0) << "nothing reaches the threshold";
  EXPECT_TRUE(softmaxWeights({}, 0.05, 0.1).empty());
}

TEST(Forcelets, DominantIsTheFirstLargestPositiveWeight)
{
  EXPECT_EQ(dominantIndex({0.1, 0.4, 0.4, 0.1}), 1);
  EXPECT_EQ(dominantIndex({0.0, 0.0}), -1);
  EXPECT_EQ(dominantIndex({}), -1);
}

TEST(Forcelets, SelectionPersistsUntilARivalBeatsTheBonus)
{
  const double bonus = 1.0;
  std::vector<double> w = {0.3, 0.5, 0.2};
  EXPECT_EQ(selectWithPersistence(w, -1, bonus), 1) << "nothing selected: the dominant one";
  EXPECT_DOUBLE_EQ(w[1], 1.0) << "boosted by 1 + bonus";
  w = {0.3, 0.5, 0.2};
  EXPECT_EQ(selectWithPersistence(w, 0, bonus), 0) << "0.5 does not beat 0.3 x 2";
  EXPECT_DOUBLE_EQ(w[0], 0.6);
  w = {0.2, 0.7, 0.1};
  EXPECT_EQ(selectWithPersistence(w, 0, bonus), 1) << "0.7 beats 0.2 x 2";
  w = {0.0, 0.6, 0.4};
  EXPECT_EQ(selectWithPersistence(w, 0, bonus), 1) << "the selected one lost its weight";
  w = {0.0, 0.0};
  EXPECT_EQ(selectWithPersistence(w, 1, bonus), -1);
  w = {0.2, 0.8};
  EXPECT_EQ(selectWithPersistence(w, 7, bonus), 1) << "out of range = none";
}

TEST(Forcelets, NineSectorsOfTheThesis)
{
  for (int i = 0; i < 9; ++i)
  {
    EXPECT_NEAR(sectorCentre(i, 9, M_PI), deg(-80 + 20 * i), 1e-12);
    EXPECT_EQ(sectorOf(sectorCentre(i, 9, M_PI), 9, M_PI), i);
  }
  EXPECT_EQ(sectorOf(deg(-95), 9, M_PI), 0);
  EXPECT_EQ(sectorOf(deg(95), 9, M_PI), 8);
  EXPECT_EQ(sectorOf(deg(-70.001), 9, M_PI), 0);
  EXPECT_EQ(sectorOf(deg(-69.999), 9, M_PI), 1);
  EXPECT_EQ(sectorOf(INFINITY, 9, M_PI), 8);
  EXPECT_EQ(sectorOf(-INFINITY, 9, M_PI), 0);
  EXPECT_EQ(sectorOf(NAN, 9, M_PI), 0);
}

// The base heading controller of §5.4 as the package README describes it: the goal attracts globally,
// each short-term-memory sector with an obstacle repels. Integrated with Euler steps.
TEST(Forcelets, BaseHeadingReachesTheGoalAndSteersAroundAnObstacle)
{
  const double alpha_a = 1.0, alpha_r = 25.0, epsilon_r = 0.34, dt = 0.05;  // thesis §5.4 values
  auto heading_after = [&](double goal, const std::vector<double>& obstacle_strength) {
    double phi = 0.0;
    for (int k = 0; k < 2000; ++k)
    {
      double rate = sineAttraction(phi, goal, alpha_a);
      for (int i = 0; i < 9; ++i)
        rate += repulsion(phi, sectorCentre(i, 9, M_PI), alpha_r, obstacle_strength[i], epsilon_r);
      phi += dt * std::clamp(rate, -1.0, 1.0);
    }
    return phi;
  };
  std::vector<double> free(9, 0.0);
  EXPECT_NEAR(heading_after(deg(50), free), deg(50), 1e-3) << "no obstacle: heads for the goal";
  std::vector<double> blocked(9, 0.0);
  blocked[sectorOf(deg(5), 9, M_PI)] = 0.2;  // an obstacle straight ahead (sector centred at 0)
  const double phi = heading_after(deg(5), blocked);
  EXPECT_GT(phi, deg(5)) << "goal slightly left of the obstacle: passes it on the left";
  EXPECT_GT(std::abs(phi), deg(10)) << "kept away from the obstacle's direction";
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
