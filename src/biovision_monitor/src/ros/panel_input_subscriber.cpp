#include "biovision_monitor/ros/panel_input_subscriber.hpp"

#include <algorithm>

namespace biovision_monitor
{
using P = PanelRenderer;
using ImageCallback = boost::function<void(const sensor_msgs::ImageConstPtr&)>;

void PanelInputSubscriber::arrived(std::initializer_list<PanelRenderer::Panel> panels)
{
  const ros::Time now = ros::Time::now();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto p : panels)
      inputs_.received[p] = now;
  }
  if (on_input_)
    for (auto p : panels)
      on_input_(p);
}

void PanelInputSubscriber::subscribe(ros::NodeHandle& nh, image_transport::ImageTransport& it,
                                     const image_transport::TransportHints& hints,
                                     const std::vector<PanelRenderer::Panel>& panels, Callback on_input)
{
  on_input_ = std::move(on_input);
  auto wants = [&](P::Panel p) { return std::find(panels.begin(), panels.end(), p) != panels.end(); };
  auto store = [this](auto& slot, const auto& message) {
    std::lock_guard<std::mutex> lock(mutex_);
    slot = message;
  };
  if (wants(P::kLeftImage))
  {
    image_subscribers_.push_back(it.subscribe(P::defaultTopic(P::kLeftImage), 1,
                                              ImageCallback([this, store](const sensor_msgs::ImageConstPtr& m) {
                                                store(inputs_.left, m);
                                                arrived({P::kLeftImage});
                                              }),
                                              ros::VoidPtr(), hints));
    subscribers_.push_back(nh.subscribe<biovision_msgs::RecognizedObjectArray>(
        "objects", 1,
        [this, store](const biovision_msgs::RecognizedObjectArrayConstPtr& m) { store(inputs_.objects, m); }));
  }
  const bool map = wants(P::kSaliencyMap), thresholded = wants(P::kThresholdedSaliency);
  if (map || thresholded)
    image_subscribers_.push_back(
        it.subscribe(P::defaultTopic(P::kSaliencyMap), 1,
                     ImageCallback([this, store, map, thresholded](const sensor_msgs::ImageConstPtr& m) {
                       store(inputs_.saliency, m);
                       if (map && thresholded)
                         arrived({P::kSaliencyMap, P::kThresholdedSaliency});
                       else
                         arrived({map ? P::kSaliencyMap : P::kThresholdedSaliency});
                     }),
                     ros::VoidPtr(), hints));
  if (thresholded)
    subscribers_.push_back(nh.subscribe<biovision_msgs::SalientRegionArray>(
        "saliency/regions", 1,
        [this, store](const biovision_msgs::SalientRegionArrayConstPtr& m) { store(inputs_.regions, m); }));
  if (wants(P::kDisparity))
    subscribers_.push_back(nh.subscribe<stereo_msgs::DisparityImage>(
        P::defaultTopic(P::kDisparity), 1, [this, store](const stereo_msgs::DisparityImageConstPtr& m) {
          store(inputs_.disparity, m);
          arrived({P::kDisparity});
        }));
  if (wants(P::kBaseAttractor))
    subscribers_.push_back(nh.subscribe<biovision_msgs::AttractorState>(
        P::defaultTopic(P::kBaseAttractor), 1, [this, store](const biovision_msgs::AttractorStateConstPtr& m) {
          store(inputs_.base, m);
          arrived({P::kBaseAttractor});
        }));
  if (wants(P::kHeadAttractor))
    subscribers_.push_back(nh.subscribe<biovision_msgs::AttractorState>(
        P::defaultTopic(P::kHeadAttractor), 1, [this, store](const biovision_msgs::AttractorStateConstPtr& m) {
          store(inputs_.head, m);
          arrived({P::kHeadAttractor});
        }));
  if (wants(P::kLtm))
    subscribers_.push_back(nh.subscribe<nav_msgs::OccupancyGrid>(
        P::defaultTopic(P::kLtm), 1, [this, store](const nav_msgs::OccupancyGridConstPtr& m) {
          store(inputs_.ltm, m);
          arrived({P::kLtm});
        }));
  if (wants(P::kStm))
    subscribers_.push_back(nh.subscribe<biovision_msgs::EgoMap>(P::defaultTopic(P::kStm), 1,
                                                                [this, store](const biovision_msgs::EgoMapConstPtr& m) {
                                                                  store(inputs_.stm, m);
                                                                  arrived({P::kStm});
                                                                }));
}

void PanelInputSubscriber::shutdown()
{
  for (auto& s : subscribers_)
    s.shutdown();
  for (auto& s : image_subscribers_)
    s.shutdown();
  subscribers_.clear();
  image_subscribers_.clear();
}

PanelRenderer::Inputs PanelInputSubscriber::snapshot() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return inputs_;
}

void PanelInputSubscriber::clear()
{
  std::lock_guard<std::mutex> lock(mutex_);
  inputs_ = PanelRenderer::Inputs();
}

std::array<std::string, PanelRenderer::kPanels> PanelInputSubscriber::resolvedTopics(const ros::NodeHandle& nh)
{
  std::array<std::string, PanelRenderer::kPanels> topics;
  for (int i = 0; i < PanelRenderer::kPanels; ++i)
    topics[i] = nh.resolveName(P::defaultTopic(P::Panel(i)));
  return topics;
}
}  // namespace biovision_monitor
