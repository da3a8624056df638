#pragma once

#include <functional>
#include <memory>
#include <string>

#include <diagnostic_updater/diagnostic_updater.h>
#include <diagnostic_updater/publisher.h>
#include <ros/ros.h>

#include "biovision_v1/ros/processing_health.hpp"

namespace biovision_v1
{
/// The diagnostics every BioVision nodelet publishes the same way: one status (ERROR for a while after
/// bad input, else idle/working) with the nodelet's own keys, the output rate against
/// ~diagnostics_min_rate / ~diagnostics_max_rate, updated once a second.
class NodeletDiagnostics
{
public:
  using Details = std::function<void(diagnostic_updater::DiagnosticStatusWrapper&)>;
  using Idle = std::function<bool()>;

  /// status: the status name ("V1 cells"); rate_topic: the output whose rate is watched; idle(): true
  /// while nobody listens; details(): adds the nodelet's keys; on_tick(): runs before each update.
  void init(ros::NodeHandle& nh, ros::NodeHandle& pnh, const std::string& node_name, const std::string& status,
            const std::string& rate_topic, double default_max_rate, Idle idle, const std::string& idle_message,
            const std::string& working_message, Details details, std::function<void()> on_tick = {})
  {
    pnh.param("diagnostics_min_rate", min_rate_, 1.0);
    pnh.param("diagnostics_max_rate", max_rate_, default_max_rate);
    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, pnh, node_name);
    updater_->setHardwareID("none");
    updater_->add(status, [this, idle, idle_message, working_message, details](diagnostic_updater::DiagnosticStatusWrapper& s) {
      health_.summarize(s, idle(), idle_message, working_message);
      details(s);
    });
    rate_ = std::make_unique<diagnostic_updater::HeaderlessTopicDiagnostic>(
        rate_topic, *updater_, diagnostic_updater::FrequencyStatusParam(&min_rate_, &max_rate_, 0.1, 10));
    timer_ = nh.createTimer(ros::Duration(1.0), [this, on_tick](const ros::TimerEvent&) {
      if (on_tick)
        on_tick();
      updater_->update();
    });
  }

  /// One output message published.
  void tick() { rate_->tick(); }
  ProcessingHealth& health() { return health_; }

private:
  ProcessingHealth health_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  std::unique_ptr<diagnostic_updater::HeaderlessTopicDiagnostic> rate_;
  ros::Timer timer_;
  double min_rate_ = 1.0, max_rate_ = 100.0;
};
}  // namespace biovision_v1
