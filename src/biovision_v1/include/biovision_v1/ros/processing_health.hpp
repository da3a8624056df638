#pragma once

#include <mutex>
#include <string>

#include <diagnostic_updater/DiagnosticStatusWrapper.h>
#include <ros/console.h>
#include <ros/time.h>

namespace biovision_v1
{
/// The error state every BioVision nodelet reports the same way: the last error with its time, a
/// throttled log line when it happens, and a diagnostic summary that stays ERROR for `hold` seconds
/// after it. Thread-safe.
class ProcessingHealth
{
public:
  explicit ProcessingHealth(double hold_seconds = 10.0) : hold_(hold_seconds) {}

  /// Records an error; logs it at most every 5 s under `logger_name` (the nodelet's name).
  void reportError(const std::string& logger_name, const std::string& what)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    last_error_ = what;
    last_error_time_ = ros::Time::now();
    ROS_ERROR_STREAM_THROTTLE_NAMED(5.0, logger_name, logger_name << ": " << what);
  }

  /// Summary: ERROR with the last error while it is recent, else OK with `idle_message` when idle,
  /// else OK with `working_message`. Adds the last error as a key.
  void summarize(diagnostic_updater::DiagnosticStatusWrapper& status, bool idle, const std::string& idle_message,
                 const std::string& working_message) const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const bool recent = !last_error_.empty() && (ros::Time::now() - last_error_time_).toSec() < hold_;
    if (recent)
      status.summary(diagnostic_msgs::DiagnosticStatus::ERROR, last_error_);
    else
      status.summary(diagnostic_msgs::DiagnosticStatus::OK, idle ? idle_message : working_message);
    status.add("last error", last_error_);
  }

private:
  double hold_;
  mutable std::mutex mutex_;
  std::string last_error_;
  ros::Time last_error_time_;
};
}  // namespace biovision_v1
