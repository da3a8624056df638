#pragma once

#include <string>

namespace biovision_attractor
{
/// The head controller's own settings (the attractor's are HeadAttractorParameters), read once at start as
/// private ROS parameters of the same names. The defaults here are the only ones written in code;
/// config/head_controller.yaml repeats them (checked by test_head_controller_config).
struct HeadControllerSettings
{
  std::string mode = "explore";              ///< initial behaviour: explore, track, look_ahead or hold
  std::string pan_joint = "head_pan_joint";  ///< URDF joint and joint_states name; commands on <pan_joint>/command
  std::string tilt_joint = "head_tilt_joint";
  double control_rate = 10.0;        ///< [Hz] control steps (ROS time)
  double joint_state_timeout = 0.5;  ///< [s] an older pan joint state holds the head (no commands)
  double min_region_area = 200.0;    ///< [px^2] smaller salient regions do not attract (thesis §4.7)
  double horizontal_fov = 0.7505;    ///< [rad] the camera's full horizontal field of view until camera_info arrives

  /// Throws std::invalid_argument naming the offending setting: an unknown mode, an empty joint name,
  /// control_rate outside (0, 1000], joint_state_timeout <= 0, min_region_area < 0, horizontal_fov outside
  /// (0, pi).
  void validate() const;
};
}  // namespace biovision_attractor
