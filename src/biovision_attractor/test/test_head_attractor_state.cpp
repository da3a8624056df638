// HeadAttractor's state handling for the node: reset() after a backward jump of time, setParameters() for
// dynamic_reconfigure.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "biovision_attractor/head_attractor.hpp"

using namespace biovision_attractor;

namespace
{
constexpr double kDt = 0.1;
constexpr double kHalfFov = 21.5 * M_PI / 180;

double deg(double d)
{
  return d * M_PI / 180;
}

std::vector<SeenRegion> look(const std::vector<double>& objects, double pan)
{
  std::vector<SeenRegion> seen;
  for (double o : objects)
    if (std::abs(o - pan) <= kHalfFov)
      seen.push_back({o, 0.2, 0.8, 1000.0});
  return seen;
}

double servo(double pan, double command)
{
  return pan + std::clamp(command - pan, -0.3, 0.3);
}

// Runs `steps` closed-loop steps from time t0 and pan; returns the commands.
std::vector<double> drive(HeadAttractor& head, const std::vector<double>& objects, double t0, int steps, double& pan)
{
  std::vector<double> commands;
  for (int k = 0; k < steps; ++k)
  {
    const auto out = head.update(look(objects, pan), pan, t0 + k * kDt, kDt, kHalfFov);
    commands.push_back(out.command);
    pan = servo(pan, out.command);
  }
  return commands;
}
}  // namespace

TEST(HeadAttractorState, ResetForgetsEverythingButParametersAndBehaviour)
{
  HeadAttractorParameters p;
  p.gain = 0.03;
  HeadAttractor used(p), fresh(p);
  // Fixating +15 deg: memory, boredom, habituation and the selection all point there.
  double pan = deg(10);
  drive(used, {deg(15)}, 0.0, 100, pan);
  used.reset();
  EXPECT_EQ(used.parameters().gain, 0.03);
  // Two equal objects: a fresh attractor takes the first of equals (-15 deg); any memory of +15 deg
  // would make it differ.
  double pan_used = 0.0, pan_fresh = 0.0;
  EXPECT_EQ(drive(used, {deg(-15), deg(15)}, 0.0, 200, pan_used),
            drive(fresh, {deg(-15), deg(15)}, 0.0, 200, pan_fresh))
      << "after reset() the attractor must behave exactly as a new one";

  HeadAttractor tracking(p);
  tracking.setBehaviour(HeadAttractor::Behaviour::kTrack, 0.3);
  tracking.reset();
  EXPECT_EQ(tracking.behaviour(), HeadAttractor::Behaviour::kTrack);
}

TEST(HeadAttractorState, ResetAfterTimeJumpsBackRestartsTheIdleClock)
{
  // Something salient until t = 50 s, nothing afterwards; at t = 100 s time restarts at 0 (a looped bag)
  // with the head at 60 deg and still nothing to see. The idle clock must not wait for t > 50 s again.
  auto pan_after_restart = [](bool reset) {
    HeadAttractor head{HeadAttractorParameters()};
    double pan = deg(45);
    drive(head, {deg(50)}, 0.0, 500, pan);
    EXPECT_NEAR(pan, deg(50), deg(3)) << "the object was not fixated: the scenario tests nothing";
    drive(head, {}, 50.0, 500, pan);
    if (reset)
      head.reset();
    pan = deg(60);
    drive(head, {}, 0.0, 150, pan);  // 15 s
    return pan;
  };
  EXPECT_LT(std::abs(pan_after_restart(true)), deg(12)) << "with reset(): straight ahead after the idle timeout";
  EXPECT_GT(std::abs(pan_after_restart(false)), deg(30)) << "without reset() the idle clock stalls (why it exists)";
}

TEST(HeadAttractorState, SetParametersValidatesAndKeepsTheState)
{
  HeadAttractorParameters p;
  HeadAttractor changed(p), same(p);
  double pan_changed = 0.0, pan_same = 0.0;
  drive(changed, {deg(15)}, 0.0, 50, pan_changed);
  drive(same, {deg(15)}, 0.0, 50, pan_same);

  HeadAttractorParameters bad = p;
  bad.look_ahead_duration = bad.look_ahead_period + 1;
  EXPECT_THROW(changed.setParameters(bad), std::invalid_argument);
  EXPECT_EQ(changed.parameters().look_ahead_duration, p.look_ahead_duration) << "rejected: previous parameters kept";
  changed.setParameters(p);  // valid and equal: nothing changes
  EXPECT_EQ(drive(changed, {deg(15), deg(-15)}, 5.0, 100, pan_changed),
            drive(same, {deg(15), deg(-15)}, 5.0, 100, pan_same))
      << "setParameters() must keep the state";

  HeadAttractorParameters slow = p;
  slow.max_rate = 0.05;
  changed.setParameters(slow);
  const auto out = changed.update({{deg(-40), 0.0, 1.0, 1000.0}}, pan_changed, 20.0, kDt, kHalfFov);
  EXPECT_LE(std::abs(out.rate), 0.05);

  HeadAttractorParameters finer = p;
  finer.sections = 18;
  changed.setParameters(finer);
  EXPECT_EQ(changed.sectionAngles().size(), 18u);
  EXPECT_EQ(changed.update({}, 0.0, 21.0, kDt, kHalfFov).attraction.size(), 18u) << "state resized with the sections";
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

TEST(HeadAttractorState, ANonFiniteTrackAngleIsRefusedAndCannotFreezeTheAttractor)
{
  // Issue #23 item 8: track of a NaN direction, then explore, left the rate at exactly 0 for good.
  HeadAttractor head{HeadAttractorParameters()};
  for (double bad : {std::nan(""), HUGE_VAL, -HUGE_VAL})
    EXPECT_THROW(head.setBehaviour(HeadAttractor::Behaviour::kTrack, bad), std::invalid_argument);
  EXPECT_EQ(head.behaviour(), HeadAttractor::Behaviour::kExplore) << "a refused call must not change the behaviour";
  head.setBehaviour(HeadAttractor::Behaviour::kExplore);
  double pan = 0.0;
  const auto commands = drive(head, {0.3}, 0.0, 30, pan);
  EXPECT_GT(pan, 0.2) << "the head must turn towards a valid target 0.3 rad away";
}
