#pragma once

#include <functional>
#include <mutex>
#include <vector>

#include <ros/time.h>

namespace biovision_ros_common
{
/// Detects ROS time going backwards — a looped bag (`rosbag play -l`), a restarted simulator — and runs
/// the reset of every time-based component that registered with it (diagnostics, rate estimates,
/// inhibition of return, motion history, sync watchdogs), so none of them waits for a time that never
/// comes again. Thread-safe.
class ClockJumpGuard
{
public:
  /// `tolerance` [s]: backward steps up to this are jitter (out-of-order stamps), not a jump.
  explicit ClockJumpGuard(double tolerance = 0.0) : tolerance_(tolerance) {}

  /// Registers a reset, run (in registration order) on every backward jump.
  void onJumpBack(std::function<void()> reset);

  /// Feeds one time (ros::Time::now() or a message stamp). Returns true, after running the resets, when
  /// it lies more than `tolerance` before the latest time seen.
  bool observe(const ros::Time& time);

  /// Number of backward jumps seen so far (for diagnostics).
  unsigned jumps() const;

private:
  double tolerance_;
  mutable std::mutex mutex_;
  ros::Time latest_;
  unsigned jumps_ = 0;
  std::vector<std::function<void()>> resets_;
};
}  // namespace biovision_ros_common
