#pragma once

#include <array>
#include <string>

#include <biovision_msgs/AttractorState.h>
#include <biovision_msgs/EgoMap.h>
#include <biovision_msgs/RecognizedObjectArray.h>
#include <biovision_msgs/SalientRegionArray.h>
#include <nav_msgs/OccupancyGrid.h>
#include <opencv2/core.hpp>
#include <ros/time.h>
#include <sensor_msgs/Image.h>
#include <stereo_msgs/DisparityImage.h>

#include "biovision_monitor/monitor_parameters.hpp"

namespace biovision_monitor
{
/// The thesis's eight panels (Fig. 5.1, in its caption's order), drawn from the latest messages with the
/// core's plots. Shared by MonitorPanelNodelet, PlotNodelet and the bag_to_video tool.
class PanelRenderer
{
public:
  enum Panel
  {
    kLeftImage,            ///< stereo/left/image_rect_color, recognised objects boxed (objects)
    kSaliencyMap,          ///< saliency/map (32FC1)
    kDisparity,            ///< stereo/disparity, colour-mapped with a scale bar
    kThresholdedSaliency,  ///< saliency/map thresholded, FoA regions and IoR (saliency/regions)
    kBaseAttractor,        ///< attractor/base
    kLtm,                  ///< memory/ltm (nav_msgs/OccupancyGrid)
    kHeadAttractor,        ///< attractor/head
    kStm,                  ///< memory/stm (biovision_msgs/EgoMap)
    kPanels
  };

  /// The latest message of each input (null = none yet) and when each panel's main input last arrived.
  struct Inputs
  {
    sensor_msgs::ImageConstPtr left, saliency;
    biovision_msgs::RecognizedObjectArrayConstPtr objects;
    biovision_msgs::SalientRegionArrayConstPtr regions;
    stereo_msgs::DisparityImageConstPtr disparity;
    biovision_msgs::AttractorStateConstPtr base, head;
    nav_msgs::OccupancyGridConstPtr ltm;
    biovision_msgs::EgoMapConstPtr stm;
    std::array<ros::Time, kPanels> received;  ///< zero = never
  };

  /// Each panel's title (the thesis's name) and the relative topic of its main input.
  static const char* title(Panel p);
  static const char* defaultTopic(Panel p);
  /// Panel by its plot name (left_image, saliency_map, disparity, thresholded_saliency, base_attractor,
  /// ltm, head_attractor, stm); false when unknown.
  static bool parse(const std::string& name, Panel& out);
  static const char* name(Panel p);

  /// Throws std::invalid_argument (MonitorParameters::validate) on bad parameters.
  explicit PanelRenderer(const MonitorParameters& parameters);

  /// Panel `p` of `in` as a CV_8UC3 image of `size`; empty when its main input has not arrived. Throws
  /// std::exception (ImageConversionError, std::invalid_argument, cv::Exception) on input it cannot draw.
  cv::Mat renderTile(Panel p, const Inputs& in, cv::Size size) const;

  /// The eight panels composed (MonitorPanel). `topics` = what "no data on" names per panel (resolved);
  /// a panel older than stale_after at `now` is marked stale; a panel that throws shows the error text.
  /// `errors` (optional) receives the last error message, empty when none. A tile whose input messages
  /// are the same as at the previous call is reused, not redrawn (the memories change about once a
  /// second, the panel is composed at 5 Hz); so calls must not overlap (the callers hold a lock).
  cv::Mat renderPanel(const Inputs& in, const std::array<std::string, kPanels>& topics, const ros::Time& now,
                      std::string* errors = nullptr);

  const MonitorParameters& parameters() const { return p_; }

private:
  /// The messages tile `p` is drawn from (their addresses): equal keys = the same picture.
  static std::array<const void*, 2> inputKey(Panel p, const Inputs& in);

  MonitorParameters p_;
  std::array<std::array<const void*, 2>, kPanels> cached_keys_{};
  std::array<cv::Mat, kPanels> cached_tiles_;
};
}  // namespace biovision_monitor
