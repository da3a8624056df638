#pragma once

#include <limits>
#include <vector>

#include "biovision_attractor/base_attractor_parameters.hpp"

namespace biovision_attractor
{
/// Attractor dynamics that steer a differential-drive base (Pioneer 3DX) to a goal around the obstacles of
/// the short-term memory (thesis §5.4, with the fixes of the package README). In the robot's frame
/// (phi = 0 is the current heading, REP-103: + = left):
///
///   dphi/dt = sineAttraction(0, psi_goal, alpha_goal) + sum_i repulsion(0, psi_i, 1, lambda_i, 2 sigma_i^2)
///   lambda_i = alpha_obstacle * exp(-clearance_i / decay_distance)   (0 for free space and confidence < min)
///   sigma_i  = atan(tan(width / 2) + R / (R + d_i))                                 (Bicho et al. 1998)
///
/// where d_i is sector i's obstacle distance, clearance_i = max(0, d_i - R). The dead-ahead sector's
/// repeller, which gives no torque at its centre (the printed model's symmetry trap), sits symmetry_angle
/// to the side opposite the one the robot turns to: the side with more clearance in the front sectors,
/// ties broken towards the goal, kept while the way ahead stays blocked (hysteresis). The forcelets are
/// those of forcelets.hpp. The rate is clamped to max_angular and slewed by angular_accel.
///
/// Forward speed (beyond the thesis): the least of max_linear; a linear fall to 0 as the goal bearing
/// reaches heading_stop_angle; a linear fall to 0 as the clearance in the swept corridor ahead falls from
/// slow_distance to safety_distance, and the speed that can still brake by then; the speed that brakes
/// onto the goal. Slewed by linear_accel, except that a clearance below safety_distance stops at once.
/// The corridor is R + corridor_margin to either side; an obstacle in its margin alone (one the disc R
/// going straight would pass) slows the base to margin_speed but does not stop it while the base turns
/// away from it or not at all: the clearance in the disc's own path (contact_clearance) below
/// safety_distance stops it, and so does the margin's when turning towards it (margin_speed 0: always).
/// The base never reverses. Once the goal is heading_stop_angle off, the base turns in place by the goal's
/// attraction alone (no repellers) until the goal is within turn_in_place_angle; newGoal() keeps that turn
/// (a waypoint moving a little must not end it), reset(), idle and reached end it.
///
/// Trap detection: when the goal distance has not fallen by trap_progress for trap_time (a bearing-only
/// goal: when the robot has not moved forward by trap_progress for trap_time), the status is kTrapped for
/// escape_time: the dynamics steer to a heading a quarter turn towards the freer side (turning in place
/// first, as the speed falls with the heading error), around obstacles as usual; the clock then restarts.
/// The speed also falls with the commanded turn rate (turn_slowdown): arcs sweep sides not seen.
///
/// Never throws from update(); never commands beyond the limits or NaN (property-tested).
class BaseAttractor
{
public:
  enum class Status
  {
    kIdle,     ///< no valid goal: stopped
    kDriving,  ///< heading for the goal
    kBlocked,  ///< an obstacle closer than safety_distance ahead: turning only
    kTrapped,  ///< no progress for trap_time: escaping towards the freer side
    kReached   ///< within goal_tolerance: stopped
  };

  /// One sector of the short-term memory (biovision_msgs/EgoMap), base_link frame.
  struct Sector
  {
    double angle = 0.0;       ///< centre [rad, + = left]
    double distance = 0.0;    ///< nearest obstacle [m]; +Inf = free; NaN = unknown (ignored, counted invalid)
    double confidence = 1.0;  ///< [0, 1]; NaN counts as 0
    double width = BaseAttractorParameters::kSectorWidth;  ///< angular width [rad] (EgoMap section_width)
    /// The least distance [m] of the sector's obstacle points from the line ahead (EgoMap obstacle_offset);
    /// NaN or negative = not known: the obstacle is assumed at the sector's edge nearest the heading, a bound
    /// that is up to a whole width pessimistic.
    double offset = std::numeric_limits<double>::quiet_NaN();
  };

  struct Output
  {
    double linear = 0.0;             ///< commanded forward speed [m/s], in [0, max_linear]
    double angular = 0.0;            ///< commanded turn rate [rad/s, + = left], |.| <= max_angular
    double heading_rate = 0.0;       ///< the dynamics' dphi/dt before the limits [rad/s]
    double goal_forcelet = 0.0;      ///< the goal attraction's share of heading_rate [rad/s]
    double target_speed = 0.0;       ///< the forward speed the dynamics head for [m/s]
    double front_clearance = 0.0;    ///< [m] clearance in the swept corridor ahead (+Inf: free)
    double contact_clearance = 0.0;  ///< [m] the same in the path of the disc R alone, no margin (+Inf: free)
    int turn_side = 0;               ///< +1 left / -1 right: where a dead-ahead obstacle is passed; 0 none
    int invalid_sectors = 0;         ///< sectors ignored for a NaN/Inf angle or a NaN distance
    Status status = Status::kIdle;
    std::vector<double> angle, strength, sigma, forcelet;  ///< per input sector: where the repeller sits [rad],
                                                           ///< lambda_i [1/s], sigma_i [rad], f_i [rad/s]
  };

  /// Throws std::invalid_argument (BaseAttractorParameters::validate).
  explicit BaseAttractor(const BaseAttractorParameters& parameters);

  /// One control step at time t [s], dt [s] after the previous one (non-finite or negative: 0, above 1:
  /// 1). goal_bearing [rad, base_link, + = left] and goal_distance [m] (+Inf: a bearing-only goal, never
  /// reached); a non-finite bearing or a NaN or negative distance: kIdle, stopping (slewed).
  Output update(const std::vector<Sector>& stm, double goal_bearing, double goal_distance, double t, double dt);

  /// Sets the commands to zero at once (watchdog, bumper, hold, stop): the next update starts from rest.
  void stop();
  /// A new goal: forgets progress, the trap clock and the chosen side.
  void newGoal();
  /// Everything learnt over time (a backward jump of time): as at construction, keeping the parameters.
  void reset();
  /// Throws std::invalid_argument, keeping the previous parameters.
  void setParameters(const BaseAttractorParameters& parameters);
  const BaseAttractorParameters& parameters() const { return p_; }
  static const char* name(Status status);

private:
  /// The clearance [m] (distance less R) of the nearest obstacle whose sector holds a point within half_width
  /// of the line ahead (+Inf: none); side +1 / -1: only the sectors left / right of it (and dead ahead), 0: all.
  /// use_offset: a sector's points lie Sector::offset off the line where known (never nearer than its edge
  /// puts them); false: at its edge.
  double clearanceAhead(const std::vector<Sector>& stm, double half_width, int side, bool use_offset) const;
  int freerSide(const std::vector<Sector>& stm, double goal_bearing) const;
  bool blindAhead(const std::vector<Sector>& stm) const;
  /// The turn rate [rad/s] from which angular_accel * turn_brake_share stops the heading at the attractor it
  /// turns into: the nearest heading in the turn's direction where the field (goal and out's repellers, or the
  /// goal alone) changes sign; pi away when none.
  double turnBrakeLimit(const Output& out, double goal_bearing, bool goal_alone) const;
  void updateTrapClock(double goal_distance, double t);

  BaseAttractorParameters p_;
  double linear_ = 0.0, angular_ = 0.0;  // last commands
  int side_ = 0;                         // chosen side for a dead-ahead obstacle, 0 = none yet
  bool clock_started_ = false;
  double best_distance_ = 0.0;  // smallest goal distance so far [m]
  double progress_time_ = 0.0;  // when progress was last made [s]
  double escape_until_ = -1.0;  // [s] trapped until then
  int escape_side_ = 1;
  bool turning_in_place_ = false;  // the goal was heading_stop_angle off: turning in place towards it
  double travelled_ = 0.0;         // [m] commanded forward travel (progress towards a bearing-only goal)
  double heading_ = 0.0;           // [rad] integrated commanded turn rate since the goal was set
  double escape_heading_ = 0.0;    // [rad] in the same reckoning: where an escape heads
};
}  // namespace biovision_attractor
