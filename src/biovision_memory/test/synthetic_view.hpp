#pragma once
// Test helper: exact disparity maps of a flat floor with vertical cylinders, seen by a camera on a
// pan/tilt head, so the memory tests know the true answer without the simulator.
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "biovision_memory/disparity_camera.hpp"

namespace biovision_memory_test
{
struct Cylinder
{
  double x, y, radius, height;  // base_link [m]
};

/// The left optical frame in base_link for a head at `height` [m], panned (+ = left) and tilted
/// (+ = down) [rad].
inline Eigen::Isometry3d cameraPose(double pan, double tilt, double height = 1.1)
{
  Eigen::Matrix3d optical;
  optical << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(pan, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix() *
               optical;
  T.translation() << 0.0, 0.0, height;
  return T;
}

/// 160×120, 43° horizontal field of view, 0.12 m baseline (the thesis's disparity resolution).
inline biovision_memory::DisparityCamera camera160()
{
  biovision_memory::DisparityCamera c;
  c.fx = c.fy = 80.0 / std::tan(21.5 * M_PI / 180.0);
  c.cx = 79.5;
  c.cy = 59.5;
  c.baseline = 0.12;
  return c;
}

/// Ray-cast disparity: the floor (z = 0, up to `floor_extent` m away) and the cylinders; −1 where the
/// ray meets nothing.
inline cv::Mat renderDisparity(const biovision_memory::DisparityCamera& cam, const Eigen::Isometry3d& base_from_camera,
                               const std::vector<Cylinder>& cylinders, double floor_extent = 30.0, int width = 160,
                               int height = 120)
{
  cv::Mat d(height, width, CV_32F, cv::Scalar(-1.0f));
  const Eigen::Vector3d o = base_from_camera.translation();
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u)
    {
      const Eigen::Vector3d ray_c((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);  // z = 1
      const Eigen::Vector3d r = base_from_camera.linear() * ray_c;
      double best = std::numeric_limits<double>::infinity();
      if (r.z() < 0)
      {
        const double t = -o.z() / r.z();
        const Eigen::Vector3d p = o + t * r;
        if (std::hypot(p.x(), p.y()) < floor_extent)
          best = t;
      }
      for (const Cylinder& c : cylinders)
      {
        // |o_xy + t r_xy − c|² = R²
        const double ax = r.x(), ay = r.y(), bx = o.x() - c.x, by = o.y() - c.y;
        const double A = ax * ax + ay * ay, B = 2 * (ax * bx + ay * by), C = bx * bx + by * by - c.radius * c.radius;
        const double disc = B * B - 4 * A * C;
        if (A <= 0 || disc < 0)
          continue;
        for (double t : {(-B - std::sqrt(disc)) / (2 * A), (-B + std::sqrt(disc)) / (2 * A)})
        {
          const double z = o.z() + t * r.z();
          if (t > 0 && z >= 0 && z <= c.height && t < best)
          {
            best = t;
            break;
          }
        }
        // top cap
        if (r.z() < 0 && o.z() > c.height)
        {
          const double t = (c.height - o.z()) / r.z();
          const Eigen::Vector3d p = o + t * r;
          if (std::hypot(p.x() - c.x, p.y() - c.y) <= c.radius && t < best)
            best = t;
        }
      }
      if (std::isfinite(best))
        d.at<float>(v, u) = static_cast<float>(cam.fx * cam.baseline / best);  // t is optical z (ray z = 1)
    }
  return d;
}
}  // namespace biovision_memory_test
