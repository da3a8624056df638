#pragma once

#include "pioneer_driver/pioneer_parameters.hpp"
#include "pioneer_driver/standard_sip.hpp"

namespace pioneer_driver
{
/// Signed difference b − a of two 15-bit position counters, wrapped into [−16384, 16383]: a jump from
/// 32760 to 5 is +13, not −32755.
int wrappedDelta15(uint16_t a, uint16_t b);

/// Odometry from standard SIPs: the wrapped 15-bit XPOS/YPOS deltas are accumulated, so the pose is
/// continuous across the counters' wrap-around; the pose is expressed relative to the first SIP (x ahead,
/// y left, yaw counter-clockwise, REP-103), velocities from the wheel speeds.
class PioneerOdometry
{
public:
  explicit PioneerOdometry(const PioneerParameters& parameters = {}) : p_(parameters) {}
  /// Adds one SIP.
  void update(const StandardSip& sip);
  /// Forgets the origin (after a reconnection the controller restarts its counters).
  void reset() { initialised_ = false; }
  bool initialised() const { return initialised_; }
  double x() const { return x_; }                ///< [m] in the odom frame
  double y() const { return y_; }                ///< [m]
  double yaw() const { return yaw_; }            ///< [rad] in (−π, π]
  double linearVelocity() const { return v_; }   ///< [m/s]
  double angularVelocity() const { return w_; }  ///< [rad/s]

private:
  PioneerParameters p_;
  bool initialised_ = false;
  uint16_t last_x_ = 0, last_y_ = 0;
  double ux_ = 0.0, uy_ = 0.0;  // accumulated controller-frame position [m]
  double yaw0_ = 0.0;
  double x_ = 0.0, y_ = 0.0, yaw_ = 0.0, v_ = 0.0, w_ = 0.0;
};

/// A Twist (m/s, rad/s) as ARCOS setpoints: VEL [mm/s] and RVEL [deg/s], each rounded and clamped to the
/// parameters' caps. A NaN or infinite input gives zero (stop), never a command.
struct ArcosVelocity
{
  int vel_mm_s = 0;
  int rvel_deg_s = 0;
  bool operator==(const ArcosVelocity& o) const { return vel_mm_s == o.vel_mm_s && rvel_deg_s == o.rvel_deg_s; }
  bool operator!=(const ArcosVelocity& o) const { return !(*this == o); }
};
ArcosVelocity toArcosVelocity(double linear_m_s, double angular_rad_s, const PioneerParameters& parameters);

/// Angle wrapped into (−π, π].
double normalizeAngle(double a);
}  // namespace pioneer_driver
