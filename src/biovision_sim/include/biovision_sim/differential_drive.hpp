#pragma once

#include <string>

#include "biovision_sim/world.hpp"

namespace biovision_sim
{
/// Differential-drive base with the Pioneer 3DX's limits: commanded (v, w) are clamped to the speed
/// limits and reached through the acceleration limits; the pose integrates exactly for constant
/// (v, w) over a step (arc). The base is a disc; moving into an obstacle's footprint stops it where it
/// was and reports the object.
class DifferentialDrive
{
public:
  struct Limits
  {
    double max_linear = 1.2;       ///< [m/s] (Pioneer 3DX: 1.2 m/s)
    double max_angular = 5.24;     ///< [rad/s] (300 deg/s)
    double linear_accel = 0.3;     ///< [m/s^2] (Pioneer 3DX default 300 mm/s^2)
    double angular_accel = 1.745;  ///< [rad/s^2] (100 deg/s^2)
    double radius = 0.26;          ///< footprint [m]
    double wheel_radius = 0.0975;  ///< [m]
    double track = 0.33;           ///< wheel separation [m]
  };

  DifferentialDrive(const Limits& limits, double x = 0, double y = 0, double yaw = 0);

  /// Commanded speeds, clamped to the limits; non-finite values stop the base.
  void command(double linear, double angular);
  /// Advances by dt; returns true when a collision stopped the base (label in collidedWith()).
  bool step(double dt, const World& world);

  double x() const { return x_; }
  double y() const { return y_; }
  double yaw() const { return yaw_; }
  double linear() const { return v_; }
  double angular() const { return w_; }
  double leftWheelAngle() const { return left_wheel_; }
  double rightWheelAngle() const { return right_wheel_; }
  const std::string& collidedWith() const { return collided_with_; }
  const Limits& limits() const { return limits_; }
  /// The label of the obstacle the footprint at (x, y) overlaps, or "" (objects with obstacle = false
  /// and objects entirely above the base's height are ignored).
  std::string obstacleAt(double x, double y, const World& world) const;

private:
  Limits limits_;
  double x_, y_, yaw_;
  double v_ = 0, w_ = 0, v_cmd_ = 0, w_cmd_ = 0;
  double left_wheel_ = 0, right_wheel_ = 0;
  std::string collided_with_;
};
}  // namespace biovision_sim
