#include "biovision_ros_common/processing_health.hpp"

#include <ros/console.h>

namespace biovision_ros_common
{
void ProcessingHealth::reportError(const std::string& logger_name, const std::string& what)
{
  std::lock_guard<std::mutex> lock(mutex_);
  last_error_ = what;
  last_error_time_ = Clock::now();
  ++errors_;
  ROS_ERROR_STREAM_THROTTLE_NAMED(5.0, logger_name, logger_name << ": " << what);
}

void ProcessingHealth::summarize(diagnostic_updater::DiagnosticStatusWrapper& status, bool idle,
                                 const std::string& idle_message, const std::string& working_message) const
{
  std::lock_guard<std::mutex> lock(mutex_);
  const bool recent = errors_ > 0 && std::chrono::duration<double>(Clock::now() - last_error_time_).count() < hold_;
  if (recent)
    status.summary(diagnostic_msgs::DiagnosticStatus::ERROR, last_error_);
  else
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, idle ? idle_message : working_message);
  status.add("last error", last_error_);
  status.add("errors since start", errors_);
}

unsigned long ProcessingHealth::errors() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return errors_;
}
}  // namespace biovision_ros_common
