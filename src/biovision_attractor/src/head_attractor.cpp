#include "biovision_attractor/head_attractor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace biovision_attractor
{
HeadAttractor::HeadAttractor(const HeadAttractorParameters& parameters)
  : p_(parameters), saliency_(parameters.sections, 0.0), repulsion_(parameters.sections, 1.0)
{
  p_.validate();
  direction_ = sectionAngles();
  tilt_.assign(p_.sections, p_.default_tilt);
  habituation_.assign(p_.sections, 0.0);
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
    case Behaviour::kExplore: return "explore";
    case Behaviour::kTrack: return "track";
    case Behaviour::kLookAhead: return "look_ahead";
    case Behaviour::kHold: return "hold";
  }
  return "?";
}

HeadAttractor::Output HeadAttractor::update(const std::vector<SeenRegion>& regions, double pan_in, double t, double dt,
                                            double half_fov, double tilt_in)
{
  const double tilt = std::isfinite(tilt_in) ? std::clamp(tilt_in, p_.tilt_lower, p_.tilt_upper) : p_.default_tilt;
  const int n = p_.sections;
  const double pan = std::isfinite(pan_in) ? std::clamp(pan_in, p_.pan_lower, p_.pan_upper) : 0.0;
  dt = std::isfinite(dt) ? std::clamp(dt, 0.0, 1.0) : 0.0;
  Output out;
  out.target = std::numeric_limits<double>::quiet_NaN();

  // Attraction A_s: in-view sections take this frame's strongest region; the others fade.
  std::vector<double> seen(n, 0.0), seen_at = direction_, seen_tilt = tilt_;
  for (const SeenRegion& r : regions)
    if (std::isfinite(r.pan) && std::isfinite(r.peak) && r.peak > 0)
    {
      const int i = p_.sectionOf(r.pan);
      if (r.peak > seen[i])
      {
        seen[i] = std::min(1.0, r.peak);
        seen_at[i] = std::clamp(r.pan, p_.pan_lower, p_.pan_upper);
        if (std::isfinite(r.tilt))
          seen_tilt[i] = std::clamp(r.tilt, p_.tilt_lower, p_.tilt_upper);
      }
    }
  const double fade = std::exp(-p_.memory_decay * dt);
  for (int i = 0; i < n; ++i)
  {
    const double angle = p_.sectionAngle(i);
    const bool in_view = std::abs(angle - pan) <= half_fov;
    if (!in_view)
    {
      saliency_[i] *= fade;
      continue;
    }
    const double before = saliency_[i];
    saliency_[i] = p_.smoothing * before + (1 - p_.smoothing) * seen[i];
    if (seen[i] > 0)
    {
      direction_[i] = before > 0 ? p_.smoothing * direction_[i] + (1 - p_.smoothing) * seen_at[i] : seen_at[i];
      tilt_[i] = before > 0 ? p_.smoothing * tilt_[i] + (1 - p_.smoothing) * seen_tilt[i] : seen_tilt[i];
    }
    else if (saliency_[i] < p_.min_saliency)
    {
      direction_[i] = angle;
      tilt_[i] = p_.default_tilt;
    }
  }

  // Repulsion A_r (1 = none): the section the head looks at grows more repulsive every frame, the
  // others recover (thesis: +-5% of the minimum repulsion per frame).
  const int here = p_.sectionOf(pan);
  for (int i = 0; i < n; ++i)
    repulsion_[i] = std::clamp(repulsion_[i] + (i == here ? -p_.repulsion_step : p_.repulsion_step), 0.0, 1.0);

  if (*std::max_element(saliency_.begin(), saliency_.end()) >= p_.min_saliency)
    last_salient_time_ = t;
  if (last_salient_time_ < -1e299)
    last_salient_time_ = t;  // the idle clock starts with the first update
  // Habituation of the fixated target; every other target recovers.
  for (int i = 0; i < n; ++i)
  {
    const bool fixated = i == selected_ && std::abs(direction_[i] - pan) < p_.fixation_radius;
    habituation_[i] = std::clamp(habituation_[i] + (fixated ? dt / p_.habituation_time : -dt / p_.recovery_time), 0.0, 0.9);
  }
  std::vector<double> attraction(n, 0.0), repulsion(n, 0.0);
  switch (behaviour_)
  {
    case Behaviour::kExplore:
      for (int i = 0; i < n; ++i)
        attraction[i] = saliency_[i] * (1.0 - habituation_[i]);
      if (t - last_salient_time_ > p_.idle_timeout)
      {
        // Nothing to look at for a while: the safe behaviour is to look where the robot goes.
        attraction[p_.sectionOf(0.0)] = 1.0;
        direction_[p_.sectionOf(0.0)] = 0.0;
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
    {
      for (int i = 0; i < n; ++i)
        attraction[i] = saliency_[i] * (1.0 - habituation_[i]);
      const bool ahead = std::fmod(t, p_.look_ahead_period) < p_.look_ahead_duration;
      if (ahead)
      {
        std::fill(attraction.begin(), attraction.end(), 0.0);
        attraction[p_.sectionOf(0.0)] = 1.0;
        direction_[p_.sectionOf(0.0)] = 0.0;
        std::fill(repulsion_.begin(), repulsion_.end(), 1.0);  // nothing pushes it away while looking ahead
      }
      break;
    }
    case Behaviour::kHold:
      break;
  }

  // Softmax weights over salient sections: the strongest dominates (the thesis' exponential).
  std::vector<double> w(n, 0.0);
  double wmax = 0.0;
  for (int i = 0; i < n; ++i)
    if (attraction[i] >= p_.min_saliency)
      wmax = std::max(wmax, attraction[i]);
  double wsum = 0.0;
  for (int i = 0; i < n; ++i)
    if (attraction[i] >= p_.min_saliency)
      wsum += w[i] = std::exp((attraction[i] - wmax) / p_.beta_attraction);
  int dominant = -1;
  for (int i = 0; i < n; ++i)
  {
    if (wsum > 0)
      w[i] /= wsum;
    if (w[i] > 0 && (dominant < 0 || w[i] > w[dominant]))
      dominant = i;
  }
  // Selection with persistence: keep the selected attractor while it is still attractive, unless a
  // rival beats its boosted weight; the selected one is boosted.
  if (selected_ < 0 || selected_ >= n || w[selected_] <= 0 ||
      (dominant >= 0 && w[dominant] > w[selected_] * (1 + p_.selection_bonus)))
    selected_ = dominant;
  if (selected_ >= 0)
  {
    w[selected_] *= 1 + p_.selection_bonus;
    dominant = selected_;
  }

  double rate = 0.0;
  out.forcelet.assign(n, 0.0);
  for (int i = 0; i < n; ++i)
  {
    const double da = direction_[i] - pan;  // attractors sit where their region was seen
    const double fa = p_.alpha_attraction * da * w[i] * std::exp(-da * da / p_.epsilon_attraction);
    const double d = p_.sectionAngle(i) - pan;  // repellers at the section (where the head dwelt)
    const double strength = std::exp((1.0 - repulsion_[i]) / p_.beta_repulsion) - 1.0;
    const double fr = -p_.alpha_repulsion * d * strength * std::exp(-d * d / p_.epsilon_repulsion);
    out.forcelet[i] = p_.gain * (fa + fr);
    rate += out.forcelet[i];
    repulsion[i] = strength;
  }
  // Walls: permanent maximal repellers just outside the head's range.
  const double wall_strength = std::exp(1.0 / p_.beta_repulsion) - 1.0;
  for (double wall : {p_.pan_lower - p_.field / p_.sections / 2, p_.pan_upper + p_.field / p_.sections / 2})
  {
    const double d = wall - pan;
    rate += -p_.gain * p_.alpha_repulsion * d * wall_strength * std::exp(-d * d / p_.wall_epsilon);
  }
  if (behaviour_ == Behaviour::kHold || !std::isfinite(rate))
    rate = 0.0;
  rate = std::clamp(rate, -p_.max_rate, p_.max_rate);
  out.rate = rate;
  out.command = std::clamp(pan + rate * dt, p_.pan_lower, p_.pan_upper);
  if (dominant >= 0 && behaviour_ != Behaviour::kHold)
  {
    out.target = direction_[dominant];
    // Saccade: a dominant attractor far from where the head looks is reached in one fast move.
    if (std::abs(out.target - pan) > p_.saccade_angle && std::abs(out.target - pan) > half_fov)
    {
      out.command = std::clamp(out.target, p_.pan_lower, p_.pan_upper);
      out.saccade = true;
    }
  }
  // Tilt: the same attractor form towards the selected target's tilt, else the default tilt.
  out.tilt_target = p_.default_tilt;
  if (p_.tilt_dynamics && dominant >= 0 && behaviour_ != Behaviour::kLookAhead)
    out.tilt_target = tilt_[dominant];
  if (behaviour_ == Behaviour::kHold)
    out.tilt_target = tilt;
  const double dt_tilt = out.tilt_target - tilt;
  double tilt_rate = p_.gain * p_.alpha_attraction * dt_tilt * std::exp(-dt_tilt * dt_tilt / p_.epsilon_attraction);
  tilt_rate = std::isfinite(tilt_rate) ? std::clamp(tilt_rate, -p_.max_rate, p_.max_rate) : 0.0;
  out.tilt_rate = tilt_rate;
  out.tilt_command = std::clamp(tilt + tilt_rate * dt, p_.tilt_lower, p_.tilt_upper);
  out.attraction = attraction;
  out.repulsion = repulsion;
  return out;
}
}  // namespace biovision_attractor
