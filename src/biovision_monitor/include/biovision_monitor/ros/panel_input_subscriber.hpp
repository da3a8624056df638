#pragma once

#include <array>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include <image_transport/image_transport.h>
#include <ros/ros.h>

#include "biovision_monitor/ros/panel_renderer.hpp"

namespace biovision_monitor
{
/// Subscribes to the inputs of a set of panels (PanelRenderer::defaultTopic, relative, so remaps move
/// them; the left image also takes `objects`, the thresholded saliency `saliency/regions`) and keeps the
/// latest message of each. Thread-safe: callbacks store, snapshot() copies the pointers.
class PanelInputSubscriber
{
public:
  /// Called after a panel's main input arrived (from the subscriber's callback thread).
  using Callback = std::function<void(PanelRenderer::Panel)>;

  void subscribe(ros::NodeHandle& nh, image_transport::ImageTransport& it, const image_transport::TransportHints& hints,
                 const std::vector<PanelRenderer::Panel>& panels, Callback on_input = {});
  void shutdown();
  /// The latest messages (pointers shared, not copied).
  PanelRenderer::Inputs snapshot() const;
  /// Drops every stored message (after a backward jump of ROS time).
  void clear();
  /// Each panel's main topic resolved in `nh` (what "no data on" names).
  static std::array<std::string, PanelRenderer::kPanels> resolvedTopics(const ros::NodeHandle& nh);

private:
  void arrived(std::initializer_list<PanelRenderer::Panel> panels);

  mutable std::mutex mutex_;
  PanelRenderer::Inputs inputs_;
  std::vector<ros::Subscriber> subscribers_;
  std::vector<image_transport::Subscriber> image_subscribers_;
  Callback on_input_;
};
}  // namespace biovision_monitor
