#pragma once

#include <memory>
#include <mutex>
#include <string>

#include <boost/thread/recursive_mutex.hpp>
#include <dynamic_reconfigure/server.h>
#include <image_transport/image_transport.h>

#include <biovision_monitor/MonitorConfig.h>

#include "biovision_monitor/ros/panel_input_subscriber.hpp"
#include "biovision_monitor/ros/panel_renderer.hpp"
#include "biovision_ros_common/lazy_nodelet.hpp"
#include "biovision_ros_common/nodelet_diagnostics.hpp"

namespace biovision_monitor
{
/// One of the eight panels as its own bgr8 image stream `monitor/<plot>` (for rviz Image displays),
/// chosen by `~plot` (PanelRenderer::parse: left_image, saliency_map, disparity, thresholded_saliency,
/// base_attractor, ltm, head_attractor, stm). Rendered when its main input arrives, at most `rate` Hz
/// (wall time); lazy: nothing subscribed or rendered while nobody listens. An unknown `~plot` is fatal
/// at start-up.
class PlotNodelet : public biovision_ros_common::LazyNodelet
{
public:
  ~PlotNodelet() override = default;

private:
  void onInitNodelet() override;
  void subscribe() override;
  void unsubscribe() override;
  void reconfigure(MonitorConfig& config, uint32_t level);
  void inputArrived(PanelRenderer::Panel panel);

  PanelRenderer::Panel panel_ = PanelRenderer::kHeadAttractor;
  std::string output_topic_, input_topic_;
  std::unique_ptr<image_transport::ImageTransport> it_;
  image_transport::Publisher image_pub_;
  PanelInputSubscriber inputs_;
  std::mutex renderer_mutex_;
  std::unique_ptr<PanelRenderer> renderer_;
  ros::WallTime last_render_;
  double last_ms_ = 0.0;
  biovision_ros_common::NodeletDiagnostics diagnostics_;
  boost::recursive_mutex reconfigure_mutex_;  // before the server: it must outlive it
  std::unique_ptr<dynamic_reconfigure::Server<MonitorConfig>> reconfigure_server_;
};
}  // namespace biovision_monitor
