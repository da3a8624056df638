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
  /// A SIP moving the robot farther than this from the previous one is implausible [m]: 6 m/s at the
  /// 100 ms SIP cycle, where ARCOS caps VEL at 2.2 m/s (the checksum is a 16-bit sum: weak).
  static constexpr double kMaxStep = 0.6;
  /// A wheel faster than this is implausible [m/s] (ARCOS's VEL cap is 2.2 m/s).
  static constexpr double kMaxWheelSpeed = 3.0;
  /// This many implausible SIPs in a row are the controller's counters restarted, not noise: the pose
  /// goes on from the newest of them.
  static constexpr int kImplausibleInARow = 3;

  explicit PioneerOdometry(const PioneerParameters& parameters = {}) : p_(parameters) {}
  /// Adds one SIP; false (pose and velocities unchanged) when it is implausible (kMaxStep, kMaxWheelSpeed).
  bool update(const StandardSip& sip);
  /// After a reconnection the controller restarts its counters: the pose goes on from where it was, the
  /// next SIP is the new counters' origin (the motion while the link was down is not seen).
  void restartCounters() { initialised_ = false; }
  bool initialised() const { return initialised_; }
  unsigned long implausible() const { return implausible_; }  ///< SIPs refused since construction
  double x() const { return x_; }                             ///< [m] in the odom frame
  double y() const { return y_; }                             ///< [m]
  double yaw() const { return yaw_; }                         ///< [rad] in (−π, π]
  double linearVelocity() const { return v_; }                ///< [m/s]
  double angularVelocity() const { return w_; }               ///< [rad/s]

private:
  PioneerParameters p_;
  bool initialised_ = false;
  uint16_t last_x_ = 0, last_y_ = 0;
  double ux_ = 0.0, uy_ = 0.0;  // accumulated controller-frame position [m] since the counters' origin
  double yaw0_ = 0.0;
  double base_x_ = 0.0, base_y_ = 0.0, base_yaw_ = 0.0;  // the pose at the counters' origin
  bool last_pose_valid_ = false;                         // x_, y_, yaw_ hold a pose (the next origin continues from it)
  int implausible_in_a_row_ = 0;
  unsigned long implausible_ = 0;
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
