#pragma once

#include <string>
#include <utility>
#include <vector>

namespace biovision_attractor
{
/// Constants of the head's attractor dynamics (thesis §4.7); every one is a parameter.
struct HeadAttractorParameters
{
  int sections = 9;                  ///< sections of the head's field, centred at -80, -60, ..., +80 deg
  double field = 3.14159265358979;   ///< [rad] the head's field (180 deg)
  double alpha_attraction = 50.0;    ///< alpha_a
  double alpha_repulsion = 50.0;     ///< alpha_r
  double beta_attraction = 0.1;      ///< softmax temperature of section saliency (saliency 0..1) [thesis: 10 on 0..255]
  double beta_repulsion = 0.5;       ///< repulsion strength exp((Ar_max - Ar)/beta) - 1
  double epsilon_attraction = 10.0;  ///< e^(-delta^2 / eps_a), delta in rad
  double epsilon_repulsion = 15.0;   ///< e^(-delta^2 / eps_r)
  double wall_epsilon = 0.02;        ///< width of the walls just outside the range: strong at +-80 deg, nil at +-60
  double repulsion_step = 0.05;      ///< per frame, fraction of Ar_max (thesis: 5%); 0 = no boredom
  double idle_timeout = 5.0;         ///< [s] nothing salient anywhere this long: look straight ahead (safe)
  double gain = 0.02;                ///< rate scale: forcelet sums (thesis units) -> rad/s
  double max_rate = 3.0;             ///< [rad/s] servo speed bound on the commanded motion
  double memory_decay = 0.1;         ///< [1/s] out-of-view sections forget saliency at this rate
  double smoothing = 0.5;        ///< in-view sections: new = smoothing * old + (1 - smoothing) * seen (regions flicker)
  double min_saliency = 0.05;    ///< sections below this do not attract
  double selection_bonus = 1.0;  ///< the selected attractor's weight is multiplied by 1 + this (persistence)
  double habituation_time = 4.0;   ///< [s] a fixated target loses its attraction over this time...
  double recovery_time = 8.0;      ///< [s] ...and regains it over this time when not fixated
  double fixation_radius = 0.12;   ///< [rad] the head fixates a target within this angle
  double saccade_angle = 0.6;      ///< [rad] a dominant attractor farther than this is reached by a saccade
  double look_ahead_period = 6.0;  ///< [s] look_ahead: the 0-deg attractor appears this often
  /// [s] and lasts this long: the base's STM then knows the way ahead more of the time (biovision_tasks'
  /// mission_eval tune seeds 101-1300, 2 / 3 s: completed 1181 / 1186, mean time 139 / 128 s, collisions 3 / 4;
  /// 4 s on 101-500: 5 collisions)
  double look_ahead_duration = 3.0;
  double pan_lower = -1.5708, pan_upper = 1.5708;    ///< [rad] joint limits (from the URDF in the node)
  double tilt_lower = -0.7854, tilt_upper = 0.7854;  ///< [rad]
  double default_tilt = 0.3;                         ///< [rad, + = down] the tilt returns here when nothing is selected
  bool tilt_dynamics = true;                         ///< false: the tilt stays at default_tilt (the thesis' fixed tilt)

  /// Throws std::invalid_argument naming the offending field.
  void validate() const;

  /// The tunable fields by the name the head controller knows them under (its private ROS parameters,
  /// config/head_controller.yaml, cfg/HeadController.cfg); default_tilt is "tilt". sections, field and the
  /// joint limits (the URDF's) are not parameters of the node.
  static const std::vector<std::pair<std::string, double HeadAttractorParameters::*>>& namedDoubles();
  static const std::vector<std::pair<std::string, bool HeadAttractorParameters::*>>& namedBools();
  /// Centre of section i [rad] (sectorCentre()).
  double sectionAngle(int i) const;
  /// The section containing `angle` [rad]; beyond the field: the end sections; NaN: section 0 (sectorOf()).
  int sectionOf(double angle) const;
};
}  // namespace biovision_attractor
