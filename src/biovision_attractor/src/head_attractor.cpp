#include "biovision_attractor/head_attractor.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <cmath>
#include <limits>

#include "biovision_attractor/forcelets.hpp"

namespace biovision_attractor
{
namespace
{
constexpr double kNever = -1e300;  // the idle clock before the first update [s]
}  // namespace

HeadAttractor::HeadAttractor(const HeadAttractorParameters& parameters) : p_(parameters)
{
  p_.validate();
  reset();
}

void HeadAttractor::reset()
{
  saliency_.assign(p_.sections, 0.0);
  direction_ = sectionAngles();
  tilt_.assign(p_.sections, p_.default_tilt);
  repulsion_.assign(p_.sections, 1.0);
  habituation_.assign(p_.sections, 0.0);
  last_salient_time_ = kNever;
  selected_ = -1;
}

void HeadAttractor::setParameters(const HeadAttractorParameters& parameters)
{
  parameters.validate();
  const bool same_sections = parameters.sections == p_.sections && parameters.field == p_.field;
  p_ = parameters;
  if (!same_sections)
    reset();  // the per-section memory belongs to the old sections
}

std::vector<double> HeadAttractor::sectionAngles() const
{
  std::vector<double> a(p_.sections);
  for (int i = 0; i < p_.sections; ++i)
    a[i] = p_.sectionAngle(i);
  return a;
}

void HeadAttractor::setBehaviour(Behaviour b, double track_angle)
{
  if (b == Behaviour::kTrack && !std::isfinite(track_angle))
    throw std::invalid_argument("HeadAttractor: track angle " + std::to_string(track_angle) + " is not finite");
  behaviour_ = b;
  track_angle_ = track_angle;
  if (b == Behaviour::kExplore)
    std::fill(repulsion_.begin(), repulsion_.end(), 1.0);
}

bool HeadAttractor::parseBehaviour(const std::string& name, Behaviour& out)
{
  if (name == "explore")
    out = Behaviour::kExplore;
  else if (name == "track")
    out = Behaviour::kTrack;
  else if (name == "look_ahead")
    out = Behaviour::kLookAhead;
  else if (name == "hold")
    out = Behaviour::kHold;
  else
    return false;
  return true;
}

const char* HeadAttractor::name(Behaviour b)
{
  switch (b)
  {
    case Behaviour::kExplore:
      return "explore";
    case Behaviour::kTrack:
      return "track";
    case Behaviour::kLookAhead:
      return "look_ahead";
    case Behaviour::kHold:
      return "hold";
  }
  return "?";
}

HeadAttractor::Output HeadAttractor::update(const std::vector<SeenRegion>& regions, double pan, double t, double dt,
                                            double half_fov, double tilt)
{
  const StepInput in = sanitise(pan, tilt, t, dt, half_fov);
  rememberSaliency(strongestPerSection(regions), in);
  inhibitReturn(in.pan);
  updateIdleClock(in.t);
  habituate(in);  // with the target selected in the previous step
  Output out;
  out.attraction = behaviourAttraction(in.t);
  std::vector<double> weights = softmaxWeights(out.attraction, p_.min_saliency, p_.beta_attraction);
  selected_ = selectWithPersistence(weights, selected_, p_.selection_bonus);
  out.rate = panRate(in.pan, weights, out);
  commandPan(in, out);
  commandTilt(in, out);
  return out;
}

HeadAttractor::StepInput HeadAttractor::sanitise(double pan, double tilt, double t, double dt, double half_fov) const
{
  StepInput in;
  in.pan = std::isfinite(pan) ? std::clamp(pan, p_.pan_lower, p_.pan_upper) : 0.0;
  in.tilt = std::isfinite(tilt) ? std::clamp(tilt, p_.tilt_lower, p_.tilt_upper) : p_.default_tilt;
  in.t = t;
  in.dt = std::isfinite(dt) ? std::clamp(dt, 0.0, 1.0) : 0.0;
  in.half_fov = half_fov;
  return in;
}

HeadAttractor::SeenPerSection HeadAttractor::strongestPerSection(const std::vector<SeenRegion>& regions) const
{
  // Sections without a region keep their remembered direction and tilt.
  SeenPerSection seen{std::vector<double>(p_.sections, 0.0), direction_, tilt_};
  for (const SeenRegion& r : regions)
  {
    if (!(std::isfinite(r.pan) && std::isfinite(r.peak) && r.peak > 0))
      continue;
    const int i = p_.sectionOf(r.pan);
    if (r.peak <= seen.peak[i])
      continue;
    seen.peak[i] = std::min(1.0, r.peak);
    seen.direction[i] = std::clamp(r.pan, p_.pan_lower, p_.pan_upper);
    if (std::isfinite(r.tilt))
      seen.tilt[i] = std::clamp(r.tilt, p_.tilt_lower, p_.tilt_upper);
  }
  return seen;
}

void HeadAttractor::rememberSaliency(const SeenPerSection& seen, const StepInput& in)
{
  // Attraction A_s: in-view sections take this frame's strongest region, low-pass filtered (regions
  // flicker); the others fade.
  const double fade = std::exp(-p_.memory_decay * in.dt);
  for (int i = 0; i < p_.sections; ++i)
  {
    const double angle = p_.sectionAngle(i);
    if (std::abs(angle - in.pan) > in.half_fov)
    {
      saliency_[i] *= fade;
      continue;
    }
    const double before = saliency_[i];
    saliency_[i] = p_.smoothing * before + (1 - p_.smoothing) * seen.peak[i];
    if (seen.peak[i] > 0)
    {
      direction_[i] = before > 0 ? p_.smoothing * direction_[i] + (1 - p_.smoothing) * seen.direction[i]
                                 : seen.direction[i];
      tilt_[i] = before > 0 ? p_.smoothing * tilt_[i] + (1 - p_.smoothing) * seen.tilt[i] : seen.tilt[i];
    }
    else if (saliency_[i] < p_.min_saliency)
    {
      // Forgotten: the attractor returns to the section's centre.
      direction_[i] = angle;
      tilt_[i] = p_.default_tilt;
    }
  }
}

void HeadAttractor::inhibitReturn(double pan)
{
  // Repulsion A_r (1 = none): the section the head looks at grows more repulsive every frame, the
  // others recover (thesis: +-5% of the minimum repulsion per frame).
  const int here = p_.sectionOf(pan);
  for (int i = 0; i < p_.sections; ++i)
    repulsion_[i] = std::clamp(repulsion_[i] + (i == here ? -p_.repulsion_step : p_.repulsion_step), 0.0, 1.0);
}

void HeadAttractor::updateIdleClock(double t)
{
  if (*std::max_element(saliency_.begin(), saliency_.end()) >= p_.min_saliency)
    last_salient_time_ = t;
  if (last_salient_time_ == kNever)
    last_salient_time_ = t;  // the idle clock starts with the first update
}

void HeadAttractor::habituate(const StepInput& in)
{
  // The fixated target (selected and within fixation_radius) habituates; every other target recovers.
  for (int i = 0; i < p_.sections; ++i)
  {
    const bool fixated = i == selected_ && std::abs(direction_[i] - in.pan) < p_.fixation_radius;
    habituation_[i] = std::clamp(habituation_[i] + (fixated ? in.dt / p_.habituation_time : -in.dt / p_.recovery_time),
                                 0.0, 0.9);
  }
}

std::vector<double> HeadAttractor::behaviourAttraction(double t)
{
  std::vector<double> attraction(p_.sections, 0.0);
  const int ahead = p_.sectionOf(0.0);
  switch (behaviour_)
  {
    case Behaviour::kExplore:
      for (int i = 0; i < p_.sections; ++i)
        attraction[i] = saliency_[i] * (1.0 - habituation_[i]);
      if (t - last_salient_time_ > p_.idle_timeout)
      {
        // Nothing to look at for a while: the safe behaviour is to look where the robot goes.
        attraction[ahead] = 1.0;
        direction_[ahead] = 0.0;
        std::fill(repulsion_.begin(), repulsion_.end(), 1.0);
      }
      break;
    case Behaviour::kTrack:
    {
      // Only the tracked direction attracts. (The thesis repels every other section instead; the
      // unequal sums of repellers on either side then throw the head off a moving target.)
      const int target = p_.sectionOf(track_angle_);
      std::fill(repulsion_.begin(), repulsion_.end(), 1.0);
      attraction[target] = 1.0;
      direction_[target] = std::clamp(track_angle_, p_.pan_lower, p_.pan_upper);
      break;
    }
    case Behaviour::kLookAhead:
      if (std::fmod(t, p_.look_ahead_period) < p_.look_ahead_duration)
      {
        attraction[ahead] = 1.0;
        direction_[ahead] = 0.0;
        std::fill(repulsion_.begin(), repulsion_.end(), 1.0);  // nothing pushes it away while looking ahead
      }
      else
        for (int i = 0; i < p_.sections; ++i)
          attraction[i] = saliency_[i] * (1.0 - habituation_[i]);
      break;
    case Behaviour::kHold:
      break;
  }
  return attraction;
}

double HeadAttractor::panRate(double pan, const std::vector<double>& weights, Output& out) const
{
  out.forcelet.assign(p_.sections, 0.0);
  out.repulsion.assign(p_.sections, 0.0);
  double rate = 0.0;
  for (int i = 0; i < p_.sections; ++i)
  {
    // Attractors sit where their region was seen, repellers at the section (where the head dwelt).
    const double strength = repulsionStrength(repulsion_[i], p_.beta_repulsion);
    const double fa = attraction(pan, direction_[i], p_.alpha_attraction, weights[i], p_.epsilon_attraction);
    const double fr = repulsion(pan, repellerAngle(i), p_.alpha_repulsion, strength, p_.epsilon_repulsion);
    out.forcelet[i] = p_.gain * (fa + fr);
    out.repulsion[i] = strength;
    rate += out.forcelet[i];
  }
  // Walls: permanent maximal repellers half a section outside the head's range.
  const double half_section = p_.field / p_.sections / 2;
  rate += p_.gain * walls(pan, p_.pan_lower - half_section, p_.pan_upper + half_section, p_.alpha_repulsion,
                          p_.beta_repulsion, p_.wall_epsilon);
  if (behaviour_ == Behaviour::kHold || !std::isfinite(rate))
    rate = 0.0;
  return std::clamp(rate, -p_.max_rate, p_.max_rate);
}

double HeadAttractor::repellerAngle(int i) const
{
  // The section holding a pan limit is inhibited from the limit (or beyond), never from its centre: a
  // repeller at the centre pushes a head dwelling between it and the limit into the limit, where the
  // target in view keeps it for good (seen in the closed-loop rostest: pinned at -90 deg on one object).
  double angle = p_.sectionAngle(i);
  if (p_.sectionOf(p_.pan_lower) == i)
    angle = std::min(angle, p_.pan_lower);
  if (p_.sectionOf(p_.pan_upper) == i)
    angle = std::max(angle, p_.pan_upper);
  return angle;
}

void HeadAttractor::commandPan(const StepInput& in, Output& out) const
{
  out.command = std::clamp(in.pan + out.rate * in.dt, p_.pan_lower, p_.pan_upper);
  out.target = std::numeric_limits<double>::quiet_NaN();
  if (selected_ < 0 || behaviour_ == Behaviour::kHold)
    return;
  out.target = direction_[selected_];
  // Saccade: a selected attractor far from where the head looks is reached in one fast move.
  if (std::abs(out.target - in.pan) > p_.saccade_angle && std::abs(out.target - in.pan) > in.half_fov)
  {
    out.command = std::clamp(out.target, p_.pan_lower, p_.pan_upper);
    out.saccade = true;
  }
}

void HeadAttractor::commandTilt(const StepInput& in, Output& out) const
{
  // The same attractor form as the pan, towards the selected target's tilt, else the default tilt.
  out.tilt_target = p_.default_tilt;
  if (p_.tilt_dynamics && selected_ >= 0 && behaviour_ != Behaviour::kLookAhead)
    out.tilt_target = tilt_[selected_];
  if (behaviour_ == Behaviour::kHold)
    out.tilt_target = in.tilt;
  const double rate = p_.gain * attraction(in.tilt, out.tilt_target, p_.alpha_attraction, 1.0, p_.epsilon_attraction);
  out.tilt_rate = std::isfinite(rate) ? std::clamp(rate, -p_.max_rate, p_.max_rate) : 0.0;
  out.tilt_command = std::clamp(in.tilt + out.tilt_rate * in.dt, p_.tilt_lower, p_.tilt_upper);
}
}  // namespace biovision_attractor
