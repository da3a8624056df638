#pragma once

namespace biovision_memory
{
/// The geometry that turns a rectified left-view disparity [px] into a point: Z = fx·baseline/d,
/// X = (u − cx)·Z/fx, Y = (v − cy)·Z/fy in the left optical frame (z forward, x right, y down).
/// From sensor_msgs/CameraInfo P (fx = P[0], cx = P[2], fy = P[5], cy = P[6]) and the stereo baseline
/// (DisparityImage.T), at the disparity map's resolution.
struct DisparityCamera
{
  double fx = 0.0;        ///< [px], > 0
  double fy = 0.0;        ///< [px], > 0
  double cx = 0.0;        ///< [px]
  double cy = 0.0;        ///< [px]
  double baseline = 0.0;  ///< [m], > 0

  /// Throws std::invalid_argument naming the field when a value is not finite or not positive.
  void validate() const;
};
}  // namespace biovision_memory
