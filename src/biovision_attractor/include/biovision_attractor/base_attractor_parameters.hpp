#pragma once

#include <string>
#include <vector>

namespace biovision_attractor
{
/// Constants of the base's attractor dynamics (thesis §5.4, read as in the package README and
/// ../shared/notes §2: the printed equations' sign, exponent and units fixed, the repeller model of
/// Bicho et al. 1998 that the thesis follows, and the forward-speed dynamics the thesis leaves out).
/// Every field is a parameter of the base_controller node (config/base_controller.yaml,
/// cfg/BaseController.cfg) under its own name. Units: metres, radians, seconds.
struct BaseAttractorParameters
{
  // Heading dynamics: dphi/dt = alpha_goal sin(psi_goal - phi) + sum_i f_i (gain 1 as in the thesis, L1310).
  double alpha_goal = 1.0;      ///< alpha_a [1/s]: goal attraction (thesis: 1)
  double alpha_obstacle = 8.0;  ///< alpha_r [1/s] (beta_1 of Bicho): repeller strength at contact; thesis 25 was
                                ///< on unknown disparity units (tuned on the tuning seeds, docs/benchmarks.md)
  double decay_distance = 0.5;  ///< beta_2 [m]: strength lambda_i = alpha_r exp(-clearance_i / beta_2)
  double robot_radius = 0.26;   ///< R [m]: Pioneer 3DX footprint; widens each repeller (sigma_i, Bicho)
  double max_range = 2.5;  ///< [m] sectors with no obstacle nearer than this do not repel (free space pushes nothing)
  double min_confidence = 0.1;   ///< sectors of lower STM confidence do not repel; above it lambda scales with it
  double symmetry_angle = 0.25;  ///< [rad] the dead-ahead sector's repeller sits this far to the side the robot
                                 ///< turns to (printed model: zero torque for an obstacle at 0 deg)
  // Forward speed (not in the thesis).
  double max_linear = 0.5;        ///< [m/s] forward speed limit (issue 16; the Pioneer 3DX can 1.2)
  double max_angular = 1.7453;    ///< [rad/s] turn-rate limit: 100 deg/s (p2os max_yawspeed)
  double linear_accel = 0.3;      ///< [m/s^2] Pioneer 3DX default 300 mm/s^2, both ways
  double angular_accel = 1.7453;  ///< [rad/s^2] 100 deg/s^2 (Pioneer 3DX default), both ways
  /// Share of angular_accel the turn may need to stop at the heading where dphi/dt next changes sign (the
  /// attractor it turns into): |turn rate| <= sqrt(2 share angular_accel distance). 0: off (the thesis' dynamics,
  /// which know no acceleration limit). Why: between a new crate and a wall 1 m apart the repellers' steep
  /// field and the slewed turn rate made a limit cycle, the heading swinging +-50 deg about the gap for 20 s
  /// until return_home failed (make demo, 2026-12-04, two runs of eight).
  double turn_brake_share = 0.8;
  double safety_distance = 0.15;  ///< [m] clearance ahead at which the robot stops (and only turns)
  double slow_distance = 1.0;     ///< [m] clearance ahead below which it slows down linearly
  double corridor_margin = 0.1;   ///< [m] the swept corridor is robot_radius + this to either side
  /// [m/s] the speed limit while an obstacle within safety_distance lies in the corridor's margin alone (the
  /// disc R going straight passes it); 0: such an obstacle stops the base, as one in its path does. Why: the
  /// base stopped 1 cm inside the margin beside a crate's corner, the waypoint dead ahead (make demo).
  double margin_speed = 0.05;
  double turn_slowdown = 2.0;    ///< [rad/s] the speed falls linearly to 0 as the commanded turn rate reaches this
  double blind_turn_rate = 0.3;  ///< [rad/s] a faster turn towards front sectors the STM does not know turns in place
  double blind_speed = 0.05;     ///< [m/s] speed limit while a sector the swept corridor crosses within blind_distance
                                 ///< is unknown to the STM: the camera glances ahead only part of the time (look_ahead)
                                 ///< and an obstacle that appeared while it looked away is not in the STM (mission_eval
                                 ///< tune seeds 101-130: no limit 8 collisions, 0.1: 3, 0.05: 0; docs/benchmarks.md)
  double blind_distance = 1.0;   ///< [m] see blind_speed
  double heading_stop_angle = 1.6;  ///< [rad] the speed falls linearly to 0 when the goal is this far off the heading
  /// [rad] once the goal is heading_stop_angle off, the base turns in place by the goal's attraction alone until
  /// it is within this angle. Why: repellers beside the base balanced the weak pull of a goal behind it, v = 0,
  /// the heading at a fixed point for 200 s (mission_eval report seed 4; tune 101-1300 completed 1166 -> 1181,
  /// collisions 14 -> 3); a disc turning in place hits nothing. At least 0.05: the goal's sine pull only nears
  /// 0 exponentially, and 0 (allowed at first) never ended the turn: the base never drove again.
  double turn_in_place_angle = 0.8;
  double goal_tolerance = 0.2;  ///< [m] reached: closer than this to the goal (then stops)
  // Trap detection (not in the thesis).
  double trap_time = 12.0;     ///< [s] no progress (goal distance not down by trap_progress) this long: trapped
  double trap_progress = 0.3;  ///< [m]
  double escape_time = 6.0;    ///< [s] a trapped robot heads a quarter turn towards the freer side this long

  /// Throws std::invalid_argument naming the offending field and its range (namedDoubles' ranges, then
  /// slow_distance > safety_distance).
  void validate() const;

  /// A parameter by name with the range validate() accepts for it alone (inclusive; > 0 is written as the
  /// smallest positive double). cfg/BaseController.cfg repeats these; test_base_controller_config checks.
  struct Named
  {
    const char* name;
    double BaseAttractorParameters::*field;
    double lower, upper;
  };
  static const std::vector<Named>& namedDoubles();

  static constexpr int kSectors = 9;                          ///< STM sectors (thesis L1298)
  static constexpr double kSectorWidth = 0.3490658503988659;  ///< [rad] 20 deg
};
}  // namespace biovision_attractor
