#include "biovision_ros_common/nodelet_diagnostics.hpp"

#include <stdexcept>

namespace biovision_ros_common
{
void NodeletDiagnostics::init(ros::NodeHandle& nh, ros::NodeHandle& pnh, const std::string& node_name,
                              DiagnosticsOptions options)
{
  if (options.status_name.empty() || options.rate_topic.empty())
    throw std::invalid_argument("NodeletDiagnostics: status_name and rate_topic are required");
  options_ = std::move(options);
  pnh.param("diagnostics_min_rate", min_rate_, 1.0);
  pnh.param("diagnostics_max_rate", max_rate_, options_.default_max_rate);
  updater_ = std::make_unique<diagnostic_updater::Updater>(nh, pnh, node_name);
  updater_->setHardwareID("none");
  updater_->add(options_.status_name, [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
    health_.summarize(s, options_.idle && options_.idle(), options_.idle_message, options_.working_message);
    s.add("ROS time jumps back", clock_jumps_.jumps());
    if (options_.details)
      options_.details(s);
  });
  rate_ = std::make_unique<diagnostic_updater::HeaderlessTopicDiagnostic>(
      options_.rate_topic, *updater_, diagnostic_updater::FrequencyStatusParam(&min_rate_, &max_rate_, 0.1, 10));
  clock_jumps_.onJumpBack([this] { rate_->clear_window(); });
  timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { publish(); });
}

void NodeletDiagnostics::tick()
{
  if (rate_)
    rate_->tick();
}

void NodeletDiagnostics::publish()
{
  clock_jumps_.observe(ros::Time::now());
  if (options_.on_tick)
    options_.on_tick();
  updater_->force_update();
}
}  // namespace biovision_ros_common
