#pragma once

#include <cmath>

namespace biovision_sim
{
/// Ideal rectified pinhole camera (no distortion). Optical frame: z forward, x right, y down.
struct PinholeCamera
{
  int width = 320;
  int height = 240;
  double fx = 0, fy = 0, cx = 0, cy = 0;

  /// A camera with the given focal length [px], square pixels and the principal point at the image
  /// centre (pixel centres at integer coordinates). No checks: StereoCalibration validates.
  static PinholeCamera fromFocalLength(int width, int height, double focal_length)
  {
    PinholeCamera c;
    c.width = width;
    c.height = height;
    c.fx = c.fy = focal_length;
    c.cx = 0.5 * (width - 1);
    c.cy = 0.5 * (height - 1);
    return c;
  }

  /// A camera with the given horizontal field of view [rad], square pixels, centred principal point.
  static PinholeCamera fromFieldOfView(int width, int height, double horizontal_fov)
  {
    return fromFocalLength(width, height, 0.5 * width / std::tan(0.5 * horizontal_fov));
  }
};
}  // namespace biovision_sim
