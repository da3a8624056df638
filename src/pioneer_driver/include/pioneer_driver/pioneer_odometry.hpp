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
  /// The fastest a wheel can go [m/s]: ARCOS caps VEL at 2.2 m/s and RVEL at 500 deg/s, which adds
  /// 1.56 m/s on each wheel of a P3-DX (diff_conv_factor 0.0056); anything faster in a SIP is a corrupted
  /// SIP with a good checksum (a 16-bit sum: weak).
  static constexpr double kMaxWheelSpeed = 4.0;
  /// The fastest turn [rad/s]: RVEL's cap, 500 deg/s.
  static constexpr double kMaxTurnRate = 8.8;
  /// Slack on a step [m] and a turn [rad] between two accepted SIPs, on top of the speeds above times the
  /// time between them (SIPs arrive bunched on a loaded machine).
  static constexpr double kStepSlack = 0.3;
  static constexpr double kTurnSlack = 0.5;
  /// This many implausible SIPs in a row are the controller's counters restarted, not noise: the pose
  /// goes on from the newest of them.
  static constexpr int kImplausibleInARow = 3;

  explicit PioneerOdometry(const PioneerParameters& parameters = {}) : p_(parameters) {}
  /// Adds one SIP received at `now` [s, any monotonic clock]; false (pose and velocities unchanged) when it
  /// is implausible: a wheel faster than kMaxWheelSpeed, or a step or turn since the last accepted SIP
  /// beyond what kMaxWheelSpeed and kMaxTurnRate allow in the time between them (plus the slack). A gap
  /// in the SIPs at speed is therefore no jump; the counters are absolute, so nothing is lost across it.
  bool update(const StandardSip& sip, double now);
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
  double last_time_ = 0.0;                               // when the last accepted SIP arrived
  double last_heading_ = 0.0;                            // its heading [rad, controller frame]
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
