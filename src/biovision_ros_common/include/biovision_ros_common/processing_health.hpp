#pragma once

#include <chrono>
#include <mutex>
#include <string>

#include <diagnostic_updater/DiagnosticStatusWrapper.h>

namespace biovision_ros_common
{
/// The error state every BioVision nodelet reports the same way: the last error, a throttled log line
/// when it happens, and a diagnostic summary that stays ERROR for `hold_seconds` of wall time after it.
/// Wall time (not ROS time), so a looped bag or a paused /clock cannot freeze or prolong the ERROR.
/// Thread-safe.
class ProcessingHealth
{
public:
  explicit ProcessingHealth(double hold_seconds = 10.0) : hold_(hold_seconds) {}

  /// Records an error; logs it at most every 5 s under `logger_name` (the nodelet's name).
  void reportError(const std::string& logger_name, const std::string& what);

  /// Summary: ERROR with the last error while it is recent, else OK with `idle_message` when idle,
  /// else OK with `working_message`. Adds the last error and the error count as keys.
  void summarize(diagnostic_updater::DiagnosticStatusWrapper& status, bool idle, const std::string& idle_message,
                 const std::string& working_message) const;

  /// Errors reported since start.
  unsigned long errors() const;

private:
  using Clock = std::chrono::steady_clock;
  double hold_;
  mutable std::mutex mutex_;
  std::string last_error_;
  Clock::time_point last_error_time_;
  unsigned long errors_ = 0;
};
}  // namespace biovision_ros_common
