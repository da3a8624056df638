#pragma once

#include <array>
#include <memory>
#include <mutex>
#include <string>

#include <boost/thread/recursive_mutex.hpp>
#include <dynamic_reconfigure/server.h>
#include <image_transport/image_transport.h>

#include <biovision_monitor/MonitorConfig.h>

#include "biovision_monitor/ros/panel_input_subscriber.hpp"
#include "biovision_monitor/ros/panel_renderer.hpp"
#include "biovision_ros_common/clock_jump_guard.hpp"
#include "biovision_ros_common/lazy_nodelet.hpp"
#include "biovision_ros_common/nodelet_diagnostics.hpp"

namespace biovision_monitor
{
/// monitor_panel: the thesis's eight panels (Fig. 5.1) composed into one bgr8 image on `monitor/panel`
/// at `rate` Hz of wall time (a paused /clock still shows the last state). Lazy: the inputs are
/// subscribed and the panel rendered only while someone listens (or ~lazy: false). With `~snapshot` set
/// to a PNG path, the panel is also written there (atomically) every `~snapshot_period` s, for run
/// reports; that needs ~lazy: false when nobody else listens.
class MonitorPanelNodelet : public biovision_ros_common::LazyNodelet
{
public:
  ~MonitorPanelNodelet() override;

private:
  void onInitNodelet() override;
  void subscribe() override;
  void unsubscribe() override;
  void reconfigure(MonitorConfig& config, uint32_t level);
  void render(const ros::WallTimerEvent&);

  std::unique_ptr<image_transport::ImageTransport> it_;
  image_transport::Publisher panel_pub_;
  PanelInputSubscriber inputs_;
  std::array<std::string, PanelRenderer::kPanels> topics_;
  ros::WallTimer timer_;
  std::mutex renderer_mutex_;
  std::unique_ptr<PanelRenderer> renderer_;
  double rate_ = 0.0;
  std::string snapshot_;
  double snapshot_period_ = 2.0;
  ros::WallTime last_snapshot_;
  double last_ms_ = 0.0;
  biovision_ros_common::ClockJumpGuard clock_jumps_;
  biovision_ros_common::NodeletDiagnostics diagnostics_;
  boost::recursive_mutex reconfigure_mutex_;  // before the server: it must outlive it
  std::unique_ptr<dynamic_reconfigure::Server<MonitorConfig>> reconfigure_server_;
};
}  // namespace biovision_monitor
