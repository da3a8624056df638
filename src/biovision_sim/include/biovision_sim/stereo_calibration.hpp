#pragma once

#include <array>

#include "biovision_sim/pinhole_camera.hpp"

namespace biovision_sim
{
/// The calibration of an ideal rectified stereo pair: two identical pinhole cameras, no distortion,
/// identity rectification, the right optical frame `baseline` metres along the left one's +x. The one
/// place the simulated cameras (`sim`, `still_camera`) compute their camera_info; ros/camera_info.hpp
/// turns a Camera into the message.
class StereoCalibration
{
public:
  /// One camera of the pair; matrices row-major, laid out as in sensor_msgs/CameraInfo.
  struct Camera
  {
    int width = 0;   ///< [px]
    int height = 0;  ///< [px]
    /// Intrinsics [fx 0 cx; 0 fy cy; 0 0 1] [px].
    std::array<double, 9> K{};
    /// Projection [fx 0 cx Tx; 0 fy cy 0; 0 0 1 0], Tx = -fx * baseline [px m] for the right camera
    /// and 0 for the left (the ROS stereo convention: disparity = -Tx / depth).
    std::array<double, 12> P{};
  };

  /// From the horizontal field of view [rad], in (0, pi). Throws std::invalid_argument naming the
  /// argument when width or height < 1, the field of view is outside (0, pi) or the baseline [m] is
  /// negative or not finite.
  static StereoCalibration fromFieldOfView(int width, int height, double horizontal_fov, double baseline);
  /// From the focal length [px], > 0 and finite; otherwise as fromFieldOfView.
  static StereoCalibration fromFocalLength(int width, int height, double focal_length, double baseline);

  /// The intrinsics both cameras share (what SceneRenderer renders with).
  const PinholeCamera& camera() const { return camera_; }
  /// Distance between the two optical centres [m].
  double baseline() const { return baseline_; }
  Camera left() const { return describe(0.0); }
  /// Equal to left() when the baseline is 0.
  Camera right() const { return describe(baseline_); }

private:
  StereoCalibration(const PinholeCamera& camera, double baseline);
  /// The camera `offset` [m] along the left one's +x.
  Camera describe(double offset) const;

  PinholeCamera camera_;
  double baseline_;
};
}  // namespace biovision_sim
