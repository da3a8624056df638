#include "biovision_sim/differential_drive.hpp"

#include <algorithm>
#include <cmath>

#include "biovision_sim/floor_plan.hpp"

namespace biovision_sim
{
DifferentialDrive::DifferentialDrive(const Limits& limits, double x, double y, double yaw)
  : limits_(limits), x_(x), y_(y), yaw_(yaw)
{
}

void DifferentialDrive::command(double linear, double angular)
{
  if (!std::isfinite(linear) || !std::isfinite(angular))
  {
    v_cmd_ = w_cmd_ = 0;
    return;
  }
  v_cmd_ = std::clamp(linear, -limits_.max_linear, limits_.max_linear);
  w_cmd_ = std::clamp(angular, -limits_.max_angular, limits_.max_angular);
}

std::string DifferentialDrive::obstacleAt(double x, double y, const World& world) const
{
  return FloorPlan(world).obstacleAt(x, y, limits_.radius);
}

bool DifferentialDrive::step(double dt, const World& world)
{
  auto approach = [dt](double current, double target, double accel) {
    return current + std::clamp(target - current, -accel * dt, accel * dt);
  };
  v_ = approach(v_, v_cmd_, limits_.linear_accel);
  w_ = approach(w_, w_cmd_, limits_.angular_accel);
  double nx, ny;
  const double nyaw = yaw_ + w_ * dt;
  if (std::abs(w_) < 1e-9)
  {
    nx = x_ + v_ * dt * std::cos(yaw_);
    ny = y_ + v_ * dt * std::sin(yaw_);
  }
  else
  {
    // Exact arc for constant (v, w) over the step.
    nx = x_ + v_ / w_ * (std::sin(nyaw) - std::sin(yaw_));
    ny = y_ - v_ / w_ * (std::cos(nyaw) - std::cos(yaw_));
  }
  const std::string hit = obstacleAt(nx, ny, world);
  if (!hit.empty() && obstacleAt(x_, y_, world).empty())
  {
    collided_with_ = hit;
    v_ = w_ = v_cmd_ = w_cmd_ = 0;
    return true;
  }
  // Wheel angles for joint_states.
  left_wheel_ += (v_ - w_ * limits_.track / 2) * dt / limits_.wheel_radius;
  right_wheel_ += (v_ + w_ * limits_.track / 2) * dt / limits_.wheel_radius;
  x_ = nx;
  y_ = ny;
  yaw_ = std::atan2(std::sin(nyaw), std::cos(nyaw));
  collided_with_.clear();
  return false;
}
}  // namespace biovision_sim
