#pragma once

#include <cmath>

#include <Eigen/Core>

namespace biovision_memory
{
/// A planar pose (x, y [m], yaw [rad], + = counter-clockwise): the base in `odom` or `map`, or a
/// transform between the two (REP-105). compose() and inverse() follow the usual SE(2) rules, so
/// `a.compose(b)` is "b expressed in a's parent frame".
struct Pose2D
{
  double x = 0.0;
  double y = 0.0;
  double yaw = 0.0;

  Pose2D compose(const Pose2D& b) const
  {
    const double c = std::cos(yaw), s = std::sin(yaw);
    return {x + c * b.x - s * b.y, y + s * b.x + c * b.y, normalizeAngle(yaw + b.yaw)};
  }
  Pose2D inverse() const
  {
    const double c = std::cos(yaw), s = std::sin(yaw);
    return {-c * x - s * y, s * x - c * y, normalizeAngle(-yaw)};
  }
  /// A point given in this pose's frame, expressed in the parent frame.
  Eigen::Vector2d apply(const Eigen::Vector2d& p) const
  {
    const double c = std::cos(yaw), s = std::sin(yaw);
    return {x + c * p.x() - s * p.y(), y + s * p.x() + c * p.y()};
  }
  bool isFinite() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(yaw); }

  /// Wraps an angle into (-pi, pi].
  static double normalizeAngle(double a)
  {
    a = std::remainder(a, 2.0 * M_PI);
    return a <= -M_PI ? a + 2.0 * M_PI : a;
  }
};
}  // namespace biovision_memory
