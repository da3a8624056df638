#pragma once

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/JointState.h>

namespace biovision_ros_common
{
/// Thrown when a calibration or joint message cannot be used; the message names the field and the problem,
/// so a nodelet can report it as is (ProcessingHealth::reportError).
struct InputError : std::invalid_argument
{
  using std::invalid_argument::invalid_argument;
};

/// The checks of camera calibrations and joint states that every BioVision nodelet applies before a value
/// enters its state: one place for "bad calibration" and "bad joints" (issue #23, items 7 and 8), so no
/// node turns a NaN, an Inf or a 1e30 into an angle it publishes. Static functions, testable without a master.
class InputCheck
{
public:
  /// [rad] largest |position| accepted for a head or arm joint: two turns either way. Beyond that the value
  /// is a damaged message, not a pose.
  static constexpr double kMaxJointAngle = 4 * M_PI;
  /// [rad] largest field of view a pinhole calibration may give (fx >= (width / 2) / tan(170° / 2)).
  static constexpr double kMaxFieldOfView = 170.0 * M_PI / 180.0;
  /// [rad] smallest field of view a pinhole calibration may give (a telescope is not a robot camera).
  static constexpr double kMinFieldOfView = 0.1 * M_PI / 180.0;

  /// Throws InputError unless `info` is a usable rectified pinhole calibration: width and height > 0; every
  /// entry of P finite; fx = P[0] and fy = P[5] > 0 and giving a field of view in
  /// [kMinFieldOfView, kMaxFieldOfView] (so fx = 1e-9 or 1e9 is refused); the principal point (P[2], P[6])
  /// within one image size of the image. When `image_width` and `image_height` are non-zero, the
  /// calibration's size must equal them. An uncalibrated camera_info (P all zero, REP-104) is refused too:
  /// the caller asked for a calibration.
  static void cameraInfo(const sensor_msgs::CameraInfo& info, uint32_t image_width = 0, uint32_t image_height = 0);

  /// The positions [rad or m] of those of `joints` that `msg` names. Throws InputError, naming the joint,
  /// when `msg` has positions but not one per name, or when a wanted joint's position is NaN/Inf or beyond
  /// ±max_abs. Joints not wanted are not looked at. A message without positions gives an empty map.
  static std::map<std::string, double> jointPositions(const sensor_msgs::JointState& msg,
                                                      const std::vector<std::string>& joints,
                                                      double max_abs = kMaxJointAngle);

  /// Throws InputError naming `what` unless `value` is finite and within ±max_abs.
  static void bounded(const std::string& what, double value, double max_abs);
};
}  // namespace biovision_ros_common
