#include "biovision_monitor/ros/panel_renderer.hpp"

#include <cstring>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "biovision_monitor/attractor_plot.hpp"
#include "biovision_monitor/disparity_plot.hpp"
#include "biovision_monitor/drawing.hpp"
#include "biovision_monitor/ego_map_plot.hpp"
#include "biovision_monitor/monitor_panel.hpp"
#include "biovision_monitor/object_plot.hpp"
#include "biovision_monitor/occupancy_grid_plot.hpp"
#include "biovision_monitor/ros/message_views.hpp"
#include "biovision_monitor/saliency_plot.hpp"
#include "biovision_ros_common/image_message_converter.hpp"

namespace biovision_monitor
{
using biovision_ros_common::ImageMessageConverter;

namespace
{
struct PanelInfo
{
  const char* name;
  const char* title;
  const char* topic;
};
const PanelInfo kInfo[PanelRenderer::kPanels] = {
    {"left_image", "left image", "stereo/left/image_rect_color"},
    {"saliency_map", "saliency map", "saliency/map"},
    {"disparity", "disparity map", "stereo/disparity"},
    {"thresholded_saliency", "thresholded saliency", "saliency/map"},
    {"base_attractor", "base attractor dynamics", "attractor/base"},
    {"ltm", "long-term memory", "memory/ltm"},
    {"head_attractor", "head attractor dynamics", "attractor/head"},
    {"stm", "short-term memory", "memory/stm"},
};
}  // namespace

const char* PanelRenderer::title(Panel p)
{
  return kInfo[p].title;
}
const char* PanelRenderer::defaultTopic(Panel p)
{
  return kInfo[p].topic;
}
const char* PanelRenderer::name(Panel p)
{
  return kInfo[p].name;
}
bool PanelRenderer::parse(const std::string& n, Panel& out)
{
  for (int i = 0; i < kPanels; ++i)
    if (n == kInfo[i].name)
    {
      out = Panel(i);
      return true;
    }
  return false;
}

PanelRenderer::PanelRenderer(const MonitorParameters& parameters) : p_(parameters)
{
  p_.validate();
}

cv::Mat PanelRenderer::renderTile(Panel p, const Inputs& in, cv::Size size) const
{
  switch (p)
  {
    case kLeftImage:
    {
      if (!in.left)
        return {};
      const cv::Mat image = ImageMessageConverter::toCv(*in.left);
      std::vector<ObjectView> objects;
      if (in.objects)
        objects = toView(*in.objects);
      return ObjectPlot().render(image, objects, size);
    }
    case kSaliencyMap:
      return in.saliency
                 ? SaliencyPlot(p_.saliency_threshold).renderMap(ImageMessageConverter::toFloat32(*in.saliency), size)
                 : cv::Mat();
    case kThresholdedSaliency:
    {
      if (!in.saliency)
        return {};
      std::vector<RegionView> regions;
      int w = 0, h = 0;
      if (in.regions)
      {
        regions = toView(*in.regions);
        w = int(in.regions->image_width);
        h = int(in.regions->image_height);
      }
      return SaliencyPlot(p_.saliency_threshold)
          .renderThresholded(ImageMessageConverter::toFloat32(*in.saliency), regions, w, h, size);
    }
    case kDisparity:
      return in.disparity ? DisparityPlot().render(ImageMessageConverter::toFloat32(in.disparity->image),
                                                   in.disparity->min_disparity, in.disparity->max_disparity, size)
                          : cv::Mat();
    case kBaseAttractor:
    case kHeadAttractor:
    {
      const auto& state = p == kBaseAttractor ? in.base : in.head;
      if (!state)
        return {};
      return AttractorPlot(p_.model(state->controller)).render(toView(*state), size);
    }
    case kLtm:
      return in.ltm ? OccupancyGridPlot().render(toView(*in.ltm), size) : cv::Mat();
    case kStm:
      return in.stm ? EgoMapPlot().render(toView(*in.stm), size) : cv::Mat();
    default:
      return {};
  }
}

std::array<const void*, 2> PanelRenderer::inputKey(Panel p, const Inputs& in)
{
  switch (p)
  {
    case kLeftImage:
      return {in.left.get(), in.objects.get()};
    case kSaliencyMap:
      return {in.saliency.get(), nullptr};
    case kThresholdedSaliency:
      return {in.saliency.get(), in.regions.get()};
    case kDisparity:
      return {in.disparity.get(), nullptr};
    case kBaseAttractor:
      return {in.base.get(), nullptr};
    case kHeadAttractor:
      return {in.head.get(), nullptr};
    case kLtm:
      return {in.ltm.get(), nullptr};
    case kStm:
      return {in.stm.get(), nullptr};
    default:
      return {nullptr, nullptr};
  }
}

cv::Mat PanelRenderer::renderPanel(const Inputs& in, const std::array<std::string, kPanels>& topics,
                                   const ros::Time& now, std::string* errors)
{
  const cv::Size size(p_.tile_width, p_.tile_height);
  std::vector<MonitorPanel::Tile> tiles(kPanels);
  if (errors)
    errors->clear();
  for (int i = 0; i < kPanels; ++i)
  {
    MonitorPanel::Tile& t = tiles[i];
    t.title = title(Panel(i));
    t.topic = topics[i];
    const auto key = inputKey(Panel(i), in);
    if (key[0] && key == cached_keys_[i] && cached_tiles_[i].size() == size)
    {
      t.image = cached_tiles_[i];
    }
    else
      try
      {
        t.image = renderTile(Panel(i), in, size);
        cached_keys_[i] = key;
        cached_tiles_[i] = t.image;
      }
      catch (const std::exception& e)
      {
        t.image = cv::Mat(size, CV_8UC3, cv::Scalar(0, 0, 120));
        putTextCentred(t.image, "cannot draw " + topics[i], size.height / 2 - 4, colours::kText, 0.45);
        putTextCentred(t.image, e.what(), size.height / 2 + 16, colours::kText, 0.35);
        if (errors)
          *errors = topics[i] + ": " + e.what();
        cached_keys_[i] = {};
      }
    const ros::Time& at = in.received[i];
    t.stale = !t.image.empty() && !at.isZero() && now >= at && (now - at).toSec() > p_.stale_after;
  }
  return MonitorPanel(p_.columns, size).compose(tiles);
}
}  // namespace biovision_monitor
