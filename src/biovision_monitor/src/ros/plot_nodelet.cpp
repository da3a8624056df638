#include "biovision_monitor/ros/plot_nodelet.hpp"

#include <chrono>
#include <stdexcept>

#include <cv_bridge/cv_bridge.h>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/image_encodings.h>

#include "biovision_monitor/ros/monitor_config.hpp"

namespace biovision_monitor
{
void PlotNodelet::onInitNodelet()
{
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  std::string plot;
  pnh.param("plot", plot, std::string("head_attractor"));
  if (!PanelRenderer::parse(plot, panel_))
  {
    NODELET_FATAL(
        "unknown ~plot '%s': left_image, saliency_map, disparity, thresholded_saliency, base_attractor, "
        "ltm, head_attractor or stm",
        plot.c_str());
    throw std::invalid_argument("unknown ~plot " + plot);
  }
  it_ = std::make_unique<image_transport::ImageTransport>(nh);
  output_topic_ = "monitor/" + plot;
  input_topic_ = PanelInputSubscriber::resolvedTopics(nh)[panel_];

  biovision_ros_common::DiagnosticsOptions options;
  options.status_name = "monitor plot " + plot;
  options.rate_topic = output_topic_;
  options.default_max_rate = 61.0;
  options.idle = [this] { return !isSubscribed(); };
  options.idle_message = "idle: nobody subscribes to " + output_topic_;
  options.working_message = "plotting " + input_topic_;
  options.details = [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
    std::lock_guard<std::mutex> lock(renderer_mutex_);
    s.add("input", input_topic_);
    s.add("last render [ms]", last_ms_);
  };
  diagnostics_.init(nh, pnh, getName(), options);

  reconfigure_server_ = std::make_unique<dynamic_reconfigure::Server<MonitorConfig>>(reconfigure_mutex_, pnh);
  reconfigure_server_->setCallback([this](MonitorConfig& c, uint32_t level) { reconfigure(c, level); });
  image_pub_ = advertiseImage(*it_, output_topic_, 1);
}

void PlotNodelet::reconfigure(MonitorConfig& config, uint32_t /*level*/)
{
  try
  {
    auto renderer = std::make_unique<PanelRenderer>(toMonitorParameters(config));
    std::lock_guard<std::mutex> lock(renderer_mutex_);
    renderer_ = std::move(renderer);
  }
  catch (const std::invalid_argument& e)
  {
    diagnostics_.health().reportError(getName(),
                                      std::string("rejected parameters (keeping the previous ones): ") + e.what());
    std::lock_guard<std::mutex> lock(renderer_mutex_);
    if (!renderer_)
      renderer_ = std::make_unique<PanelRenderer>(MonitorParameters());
  }
}

void PlotNodelet::subscribe()
{
  inputs_.subscribe(getNodeHandle(), *it_, imageHints(), {panel_}, [this](PanelRenderer::Panel p) { inputArrived(p); });
}

void PlotNodelet::unsubscribe()
{
  inputs_.shutdown();
}

void PlotNodelet::inputArrived(PanelRenderer::Panel panel)
{
  if (panel != panel_)
    return;
  const auto start = std::chrono::steady_clock::now();
  const PanelRenderer::Inputs in = inputs_.snapshot();
  cv::Mat image;
  {
    std::lock_guard<std::mutex> lock(renderer_mutex_);
    const ros::WallTime now = ros::WallTime::now();
    if ((now - last_render_).toSec() < 1.0 / renderer_->parameters().rate)
      return;
    last_render_ = now;
    try
    {
      const MonitorParameters& p = renderer_->parameters();
      image = renderer_->renderTile(panel_, in, cv::Size(p.tile_width, p.tile_height));
    }
    catch (const std::exception& e)  // ImageConversionError, invalid_argument, cv::Exception
    {
      diagnostics_.health().reportError(getName(), "cannot plot " + input_topic_ + ": " + e.what());
      return;
    }
  }
  if (image.empty())
    return;
  std_msgs::Header header;
  header.stamp = ros::Time::now();
  image_pub_.publish(cv_bridge::CvImage(header, sensor_msgs::image_encodings::BGR8, image).toImageMsg());
  diagnostics_.tick();
  std::lock_guard<std::mutex> lock(renderer_mutex_);
  last_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace biovision_monitor

PLUGINLIB_EXPORT_CLASS(biovision_monitor::PlotNodelet, nodelet::Nodelet)
