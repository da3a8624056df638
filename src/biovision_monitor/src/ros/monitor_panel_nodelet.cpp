#include "biovision_monitor/ros/monitor_panel_nodelet.hpp"

#include <chrono>
#include <vector>

#include <cv_bridge/cv_bridge.h>
#include <opencv2/imgcodecs.hpp>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/image_encodings.h>

#include "biovision_common/atomic_file.hpp"
#include "biovision_monitor/ros/monitor_config.hpp"

namespace biovision_monitor
{
MonitorPanelNodelet::~MonitorPanelNodelet()
{
  timer_.stop();
}

void MonitorPanelNodelet::onInitNodelet()
{
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  it_ = std::make_unique<image_transport::ImageTransport>(nh);
  topics_ = PanelInputSubscriber::resolvedTopics(nh);
  pnh.param("snapshot", snapshot_, std::string());
  pnh.param("snapshot_period", snapshot_period_, 2.0);

  biovision_ros_common::DiagnosticsOptions options;
  options.status_name = "monitor panel";
  options.rate_topic = "monitor/panel";
  options.default_max_rate = 61.0;
  options.idle = [this] { return !isSubscribed(); };
  options.idle_message = "idle: nobody subscribes to monitor/panel";
  options.working_message = "composing";
  options.details = [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
    std::lock_guard<std::mutex> lock(renderer_mutex_);
    s.add("rate [Hz]", rate_);
    s.add("last composition [ms]", last_ms_);
    s.add("snapshot", snapshot_.empty() ? std::string("none") : snapshot_);
  };
  diagnostics_.init(nh, pnh, getName(), options);
  // A backward jump of ROS time: the stored messages (and their ages) belong to the old time line. Seen
  // at every composition (own guard: it must not wait for the diagnostics' 1 Hz check).
  clock_jumps_.onJumpBack([this] {
    NODELET_WARN("ROS time jumped back: forgetting the stored inputs");
    inputs_.clear();
  });

  reconfigure_server_ = std::make_unique<dynamic_reconfigure::Server<MonitorConfig>>(reconfigure_mutex_, pnh);
  reconfigure_server_->setCallback([this](MonitorConfig& c, uint32_t level) { reconfigure(c, level); });
  panel_pub_ = advertiseImage(*it_, "monitor/panel", 1);
}

void MonitorPanelNodelet::reconfigure(MonitorConfig& config, uint32_t /*level*/)
{
  try
  {
    auto renderer = std::make_unique<PanelRenderer>(toMonitorParameters(config));
    std::lock_guard<std::mutex> lock(renderer_mutex_);
    const double rate = renderer->parameters().rate;
    renderer_ = std::move(renderer);
    if (rate != rate_)
    {
      rate_ = rate;
      timer_ = getNodeHandle().createWallTimer(ros::WallDuration(1.0 / rate_), &MonitorPanelNodelet::render, this);
    }
  }
  catch (const std::invalid_argument& e)
  {
    diagnostics_.health().reportError(getName(),
                                      std::string("rejected parameters (keeping the previous ones): ") + e.what());
    std::lock_guard<std::mutex> lock(renderer_mutex_);
    if (!renderer_)
    {
      renderer_ = std::make_unique<PanelRenderer>(MonitorParameters());
      rate_ = renderer_->parameters().rate;
      timer_ = getNodeHandle().createWallTimer(ros::WallDuration(1.0 / rate_), &MonitorPanelNodelet::render, this);
    }
  }
}

void MonitorPanelNodelet::subscribe()
{
  std::vector<PanelRenderer::Panel> all;
  for (int i = 0; i < PanelRenderer::kPanels; ++i)
    all.push_back(PanelRenderer::Panel(i));
  inputs_.subscribe(getNodeHandle(), *it_, imageHints(), all);
}

void MonitorPanelNodelet::unsubscribe()
{
  inputs_.shutdown();
}

void MonitorPanelNodelet::render(const ros::WallTimerEvent&)
{
  if (!isSubscribed())
    return;  // lazy: nothing rendered while nobody listens
  const auto start = std::chrono::steady_clock::now();
  clock_jumps_.observe(ros::Time::now());
  const PanelRenderer::Inputs in = inputs_.snapshot();
  std::string error;
  cv::Mat panel;
  {
    std::lock_guard<std::mutex> lock(renderer_mutex_);
    panel = renderer_->renderPanel(in, topics_, ros::Time::now(), &error);
  }
  if (!error.empty())
    diagnostics_.health().reportError(getName(), "bad input: " + error);
  std_msgs::Header header;
  header.stamp = ros::Time::now();
  panel_pub_.publish(cv_bridge::CvImage(header, sensor_msgs::image_encodings::BGR8, panel).toImageMsg());
  diagnostics_.tick();
  const ros::WallTime now = ros::WallTime::now();
  if (!snapshot_.empty() && (now - last_snapshot_).toSec() >= snapshot_period_)
  {
    last_snapshot_ = now;
    std::vector<uchar> png;
    try
    {
      cv::imencode(".png", panel, png);
      biovision_common::writeFileAtomically(snapshot_, png.data(), png.size());
    }
    catch (const std::exception& e)
    {
      diagnostics_.health().reportError(getName(), "cannot write the snapshot: " + std::string(e.what()));
    }
  }
  std::lock_guard<std::mutex> lock(renderer_mutex_);
  last_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace biovision_monitor

PLUGINLIB_EXPORT_CLASS(biovision_monitor::MonitorPanelNodelet, nodelet::Nodelet)
