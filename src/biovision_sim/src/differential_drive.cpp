#include "biovision_sim/differential_drive.hpp"

#include <algorithm>
#include <cmath>

namespace biovision_sim
{
namespace
{
constexpr double kBaseHeight = 1.2;  // the robot with its mast [m]: objects above it do not collide
}

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
  for (const auto& o : world.objects())
  {
    if (!o.obstacle || o.position.z() - o.size.z() / 2 > kBaseHeight)
      continue;
    const double dx = x - o.position.x(), dy = y - o.position.y();
    if (o.shape == "cylinder")
    {
      if (std::hypot(dx, dy) < o.size.x() / 2 + limits_.radius)
        return o.label;
      continue;
    }
    // Box: distance from the disc centre to the rotated rectangle.
    const double c = std::cos(o.yaw), s = std::sin(o.yaw);
    const double lx = c * dx + s * dy, ly = -s * dx + c * dy;
    const double qx = std::max(0.0, std::abs(lx) - o.size.x() / 2), qy = std::max(0.0, std::abs(ly) - o.size.y() / 2);
    if (std::hypot(qx, qy) < limits_.radius)
      return o.label;
  }
  return "";
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
