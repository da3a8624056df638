#include "biovision_attractor/head_attractor_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "biovision_attractor/forcelets.hpp"

namespace biovision_attractor
{
void HeadAttractorParameters::validate() const
{
  auto fail = [](const std::string& what) { throw std::invalid_argument("HeadAttractorParameters: " + what); };
  if (sections < 3 || sections > 90)
    fail("sections outside [3, 90]");
  if (!(field > 0.1 && field <= 2 * M_PI))
    fail("field outside (0.1, 2 pi]");
  if (!(alpha_attraction >= 0 && alpha_repulsion >= 0 && beta_attraction > 0 && beta_repulsion > 0))
    fail("alphas must be >= 0 and betas > 0");
  if (!(epsilon_attraction > 0 && epsilon_repulsion > 0 && wall_epsilon > 0))
    fail("epsilons must be > 0");
  if (!(repulsion_step >= 0 && repulsion_step <= 1))
    fail("repulsion_step outside [0, 1]");
  if (!(habituation_time > 0 && recovery_time > 0 && fixation_radius > 0 && selection_bonus >= 0))
    fail("habituation_time, recovery_time, fixation_radius must be > 0 and selection_bonus >= 0");
  if (!(smoothing >= 0 && smoothing < 1))
    fail("smoothing outside [0, 1)");
  if (!(idle_timeout > 0))
    fail("idle_timeout must be > 0");
  if (!(gain > 0 && max_rate > 0 && memory_decay >= 0 && min_saliency >= 0 && saccade_angle > 0))
    fail("gain, max_rate, saccade_angle must be > 0; memory_decay, min_saliency >= 0");
  if (!(look_ahead_period > 0 && look_ahead_duration >= 0 && look_ahead_duration <= look_ahead_period))
    fail("need look_ahead_period > 0 and 0 <= look_ahead_duration <= look_ahead_period");
  if (!(pan_lower < pan_upper))
    fail("pan_lower must be < pan_upper");
  if (!(tilt_lower < tilt_upper) || !(default_tilt >= tilt_lower && default_tilt <= tilt_upper))
    fail("need tilt_lower < tilt_upper and default_tilt between them");
}

const std::vector<std::pair<std::string, double HeadAttractorParameters::*>>& HeadAttractorParameters::namedDoubles()
{
  using P = HeadAttractorParameters;
  static const std::vector<std::pair<std::string, double P::*>> names = {
      {"alpha_attraction", &P::alpha_attraction},
      {"alpha_repulsion", &P::alpha_repulsion},
      {"beta_attraction", &P::beta_attraction},
      {"beta_repulsion", &P::beta_repulsion},
      {"epsilon_attraction", &P::epsilon_attraction},
      {"epsilon_repulsion", &P::epsilon_repulsion},
      {"wall_epsilon", &P::wall_epsilon},
      {"repulsion_step", &P::repulsion_step},
      {"idle_timeout", &P::idle_timeout},
      {"gain", &P::gain},
      {"max_rate", &P::max_rate},
      {"memory_decay", &P::memory_decay},
      {"smoothing", &P::smoothing},
      {"min_saliency", &P::min_saliency},
      {"selection_bonus", &P::selection_bonus},
      {"habituation_time", &P::habituation_time},
      {"recovery_time", &P::recovery_time},
      {"fixation_radius", &P::fixation_radius},
      {"saccade_angle", &P::saccade_angle},
      {"look_ahead_period", &P::look_ahead_period},
      {"look_ahead_duration", &P::look_ahead_duration},
      {"tilt", &P::default_tilt},
  };
  return names;
}

const std::vector<std::pair<std::string, bool HeadAttractorParameters::*>>& HeadAttractorParameters::namedBools()
{
  static const std::vector<std::pair<std::string, bool HeadAttractorParameters::*>> names = {
      {"tilt_dynamics", &HeadAttractorParameters::tilt_dynamics}};
  return names;
}

double HeadAttractorParameters::sectionAngle(int i) const
{
  return sectorCentre(i, sections, field);
}

int HeadAttractorParameters::sectionOf(double angle) const
{
  return sectorOf(angle, sections, field);
}
}  // namespace biovision_attractor
