#pragma once

#include <string>

namespace biovision_attractor
{
/// The base controller's own settings (the attractor's are BaseAttractorParameters), read once at start as
/// private ROS parameters of the same names. The defaults here are the only ones written in code;
/// config/base_controller.yaml repeats them (checked by test_base_controller_config).
struct BaseControllerSettings
{
  std::string odom_frame = "odom";  ///< goals are transformed into this frame (tf) and followed there
  double control_rate = 20.0;       ///< [Hz] control steps (ROS time)
  /// [s] an STM older than this (by receipt or by stamp) stops the base: with the 1/20 s step the watchdog
  /// zeroes cmd_vel within 0.4 s (issue: 0.5 s; 0.4 s timeouts measured 0.46 s in the rostest). The STM
  /// must come at more than 2.9 Hz.
  double stm_timeout = 0.35;
  double odom_timeout = 0.35;        ///< [s] the same for odometry
  double max_goal_distance = 100.0;  ///< [m] farther goals are refused as absurd

  /// Throws std::invalid_argument naming the offending setting: an empty frame, control_rate outside
  /// [1, 1000] Hz, a timeout outside (0, 10] s or below one control period, max_goal_distance <= 0.
  void validate() const;
};
}  // namespace biovision_attractor
