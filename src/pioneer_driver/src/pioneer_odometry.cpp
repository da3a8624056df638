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

void PioneerOdometry::update(const StandardSip& sip)
{
  const double heading = sip.thpos * p_.angle_conv_factor;
  if (!initialised_)
  {
    initialised_ = true;
    last_x_ = sip.xpos;
    last_y_ = sip.ypos;
    ux_ = uy_ = 0.0;
    yaw0_ = heading;
  }
  ux_ += wrappedDelta15(last_x_, sip.xpos) * p_.dist_conv_factor * 1e-3;
  uy_ += wrappedDelta15(last_y_, sip.ypos) * p_.dist_conv_factor * 1e-3;
  last_x_ = sip.xpos;
  last_y_ = sip.ypos;
  // Into the frame of the first SIP.
  const double c = std::cos(-yaw0_), s = std::sin(-yaw0_);
  x_ = c * ux_ - s * uy_;
  y_ = s * ux_ + c * uy_;
  yaw_ = normalizeAngle(heading - yaw0_);
  const double l = sip.left_velocity * p_.vel_conv_factor, r = sip.right_velocity * p_.vel_conv_factor;
  v_ = 0.5 * (l + r) * 1e-3;
  w_ = 0.5 * (r - l) * p_.diff_conv_factor;
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
