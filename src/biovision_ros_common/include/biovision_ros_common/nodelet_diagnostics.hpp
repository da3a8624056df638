#pragma once

#include <functional>
#include <memory>
#include <string>

#include <diagnostic_updater/diagnostic_updater.h>
#include <diagnostic_updater/publisher.h>
#include <ros/ros.h>

#include "biovision_ros_common/clock_jump_guard.hpp"
#include "biovision_ros_common/processing_health.hpp"

namespace biovision_ros_common
{
/// What a nodelet's diagnostics say, beyond the shared error state and output rate.
struct DiagnosticsOptions
{
  std::string status_name;          ///< the status's name, e.g. "V1 cells"
  std::string rate_topic;           ///< the output whose rate is watched
  double default_max_rate = 100.0;  ///< [Hz] default of ~diagnostics_max_rate
  std::string idle_message = "idle: nobody subscribes";
  std::string working_message = "processing";
  std::function<bool()> idle;  ///< true while nobody listens (lazy nodelets); empty = never idle
  std::function<void(diagnostic_updater::DiagnosticStatusWrapper&)> details;  ///< the nodelet's own keys
  std::function<void()> on_tick;                                              ///< runs before each update (watchdogs)
};

/// The diagnostics every BioVision nodelet publishes the same way: one status (ERROR for a while after bad
/// input, else idle/working) with the nodelet's keys, and the output rate against ~diagnostics_min_rate /
/// ~diagnostics_max_rate [Hz]. Published once a second of wall time, so a paused or looped /clock never
/// stops it (diagnostic_updater's own update() waits for a ROS time that a looped bag never reaches again);
/// on a backward jump of ROS time the rate window restarts.
class NodeletDiagnostics
{
public:
  /// Throws std::invalid_argument when the options lack a status name or rate topic.
  void init(ros::NodeHandle& nh, ros::NodeHandle& pnh, const std::string& node_name, DiagnosticsOptions options);

  /// One output message published.
  void tick();
  ProcessingHealth& health() { return health_; }
  /// Backward jumps of ROS time seen by the 1 Hz check; components register their resets here.
  ClockJumpGuard& clockJumps() { return clock_jumps_; }

private:
  void publish();

  DiagnosticsOptions options_;
  ProcessingHealth health_;
  ClockJumpGuard clock_jumps_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  std::unique_ptr<diagnostic_updater::HeaderlessTopicDiagnostic> rate_;
  ros::WallTimer timer_;
  double min_rate_ = 1.0, max_rate_ = 100.0;
};
}  // namespace biovision_ros_common
