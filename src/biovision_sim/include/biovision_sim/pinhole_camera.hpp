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

  /// A camera with the given horizontal field of view [rad], square pixels, centred principal point.
  static PinholeCamera fromFieldOfView(int width, int height, double horizontal_fov)
  {
    PinholeCamera c;
    c.width = width;
    c.height = height;
    c.fx = c.fy = 0.5 * width / std::tan(0.5 * horizontal_fov);
    c.cx = 0.5 * (width - 1);
    c.cy = 0.5 * (height - 1);
    return c;
  }
};
}  // namespace biovision_sim
