#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_attractor/base_attractor_parameters.hpp"
#include "biovision_attractor/head_attractor_parameters.hpp"
#include "biovision_sim/world.hpp"
#include "stm_source.hpp"

namespace biovision_attractor
{
/// One closed-loop navigation trial without ROS (navigation_eval, test_base_navigation): the
/// simulator's DifferentialDrive (Pioneer 3DX limits, collisions from the FloorPlan footprints) and the
/// head's pan servo, driven by BaseAttractor from an StmSource and, with an active head, by HeadAttractor in
/// look_ahead mode. Salient regions for the head are a stand-in for the saliency pipeline: the labelled
/// clutter (not walls) in the camera's view, peak 1 - distance / 6 m. With an active head the trial starts
/// with one pan sweep while the base waits (initial_scan, not counted in the time). A watchdog as the
/// node's stops the base when the STM is older than watchdog_timeout.
struct NavigationTrialOptions
{
  bool active_head = true;         ///< false: the head stays straight ahead
  double control_rate = 10.0;      ///< [Hz] base and head controller steps
  double stm_rate = 5.0;           ///< [Hz] STM updates (the camera loop)
  double physics_rate = 50.0;      ///< [Hz] drive integration
  double timeout = 120.0;          ///< [s] a trial that has not reached the goal by then fails
  double reach_radius = 0.3;       ///< [m] reached: stopped within this of the goal
  double watchdog_timeout = 0.5;   ///< [s]
  double horizontal_fov = 0.7505;  ///< [rad]
  double servo_speed = 3.0;        ///< [rad/s] the pan servo (biovision_sim's default)
  double initial_scan = 3.0;       ///< [s] active head: before the goal is given, the pan sweeps -80..+80 deg once
                                   ///< (the STM starts empty; a fixed head cannot do this)
};

struct NavigationTrialResult
{
  bool reached = false;
  double time = 0.0;                       ///< [s] until stopped at the goal (or the timeout)
  double path_length = 0.0;                ///< [m]
  double straight_line = 0.0;              ///< [m] start to goal
  double min_clearance = 0.0;              ///< [m] smallest gap between the base's disc and any footprint
  int collisions = 0;                      ///< contacts the drive reported (each stops the base)
  int watchdog_stops = 0;                  ///< control steps the watchdog zeroed the command
  int trapped_events = 0;                  ///< times the controller reported itself trapped
  double final_distance = 0.0;             ///< [m] to the goal at the end
  double mean_pan_abs = 0.0;               ///< [rad] mean |head pan| (0 for a fixed head)
  std::vector<cv::Point2d> path;           ///< [m] world frame: the start, then the base at every control step
  std::vector<cv::Point2d> collisions_at;  ///< [m] world frame: where each counted collision happened
};

/// Runs a trial from (start_x, start_y, start_yaw) to (goal_x, goal_y) in `world`. make_stm builds the STM
/// source for the world's FloorPlan (kept alive for the trial). Throws std::invalid_argument for bad
/// parameters.
NavigationTrialResult runNavigationTrial(const biovision_sim::World& world, double start_x, double start_y,
                                         double start_yaw, double goal_x, double goal_y,
                                         const BaseAttractorParameters& base, const HeadAttractorParameters& head,
                                         const NavigationTrialOptions& options,
                                         const std::function<std::unique_ptr<StmSource>()>& make_stm);
}  // namespace biovision_attractor
