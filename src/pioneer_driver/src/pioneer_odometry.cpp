#include "pioneer_driver/pioneer_odometry.hpp"

#include <algorithm>
#include <cmath>

namespace pioneer_driver
{
int wrappedDelta15(uint16_t a, uint16_t b)
{
  int d = (static_cast<int>(b & 0x7FFF) - static_cast<int>(a & 0x7FFF)) & 0x7FFF;
  return d >= 0x4000 ? d - 0x8000 : d;
}

double normalizeAngle(double a)
{
  a = std::fmod(a, 2.0 * M_PI);
  if (a <= -M_PI)
    a += 2.0 * M_PI;
  else if (a > M_PI)
    a -= 2.0 * M_PI;
  return a;
}

bool PioneerOdometry::update(const StandardSip& sip, double now)
{
  const double heading = sip.thpos * p_.angle_conv_factor;
  const double l = sip.left_velocity * p_.vel_conv_factor * 1e-3, r = sip.right_velocity * p_.vel_conv_factor * 1e-3;
  const double dx = wrappedDelta15(last_x_, sip.xpos) * p_.dist_conv_factor * 1e-3;
  const double dy = wrappedDelta15(last_y_, sip.ypos) * p_.dist_conv_factor * 1e-3;
  const double dt = std::max(0.0, now - last_time_);
  const bool wheels = std::abs(l) > kMaxWheelSpeed || std::abs(r) > kMaxWheelSpeed;
  const bool jump = initialised_ &&
                    (std::hypot(dx, dy) > kStepSlack + kMaxWheelSpeed * dt ||
                     std::abs(normalizeAngle(heading - last_heading_)) > kTurnSlack + kMaxTurnRate * dt);
  if (wheels || jump)
  {
    ++implausible_;
    // Jumps in a row are the controller's counters restarted (a reset): go on from the third. A wheel
    // speed no P3-DX reaches is never followed.
    if (wheels || ++implausible_in_a_row_ < kImplausibleInARow)
      return false;
    restartCounters();
  }
  implausible_in_a_row_ = 0;
  if (!initialised_)
  {
    // The counters' origin: the pose so far is kept and the new counters' motion is added to it.
    if (last_pose_valid_)
    {
      base_x_ = x_;
      base_y_ = y_;
      base_yaw_ = yaw_;
    }
    initialised_ = last_pose_valid_ = true;
    ux_ = uy_ = 0.0;
    yaw0_ = heading;
  }
  else
  {
    ux_ += dx;  // the step checked above
    uy_ += dy;
  }
  last_x_ = sip.xpos;
  last_y_ = sip.ypos;
  last_time_ = now;
  last_heading_ = heading;
  // Into the frame of the counters' first SIP, then onto the pose there.
  const double c = std::cos(-yaw0_), s = std::sin(-yaw0_);
  const double rx = c * ux_ - s * uy_, ry = s * ux_ + c * uy_;
  const double cb = std::cos(base_yaw_), sb = std::sin(base_yaw_);
  x_ = base_x_ + cb * rx - sb * ry;
  y_ = base_y_ + sb * rx + cb * ry;
  yaw_ = normalizeAngle(base_yaw_ + heading - yaw0_);
  v_ = 0.5 * (l + r);
  w_ = 0.5 * (r - l) * p_.diff_conv_factor * 1e3;
  return true;
}

ArcosVelocity toArcosVelocity(double linear_m_s, double angular_rad_s, const PioneerParameters& p)
{
  ArcosVelocity a;
  if (!std::isfinite(linear_m_s) || !std::isfinite(angular_rad_s))
    return a;
  const double v = std::clamp(linear_m_s, -p.max_linear_speed, p.max_linear_speed) * 1000.0;
  const double w = std::clamp(angular_rad_s, -p.max_angular_speed, p.max_angular_speed) * 180.0 / M_PI;
  // Truncate towards zero after rounding so the cap is never exceeded by rounding.
  const int vmax = static_cast<int>(std::floor(p.max_linear_speed * 1000.0 + 1e-9));
  const int wmax = static_cast<int>(std::floor(p.max_angular_speed * 180.0 / M_PI + 1e-9));
  a.vel_mm_s = std::clamp(static_cast<int>(std::lround(v)), -vmax, vmax);
  a.rvel_deg_s = std::clamp(static_cast<int>(std::lround(w)), -wmax, wmax);
  return a;
}
}  // namespace pioneer_driver
