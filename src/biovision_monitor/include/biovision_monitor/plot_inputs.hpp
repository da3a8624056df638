#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_common/grid_view.hpp"

/// What the plots draw, as plain data: the ROS-free mirror of the messages the monitor reads (the nodelets
/// fill these from biovision_msgs / nav_msgs / stereo_msgs; tests fill them by hand).
namespace biovision_monitor
{
/// biovision_msgs/AttractorState. Angles in rad, REP-103 (+ = left), 0 = straight ahead.
struct AttractorView
{
  std::string controller;              ///< "head_pan", "head_tilt" or "base"
  std::string behaviour;               ///< explore, track, goal, avoid ...
  std::vector<double> section_angles;  ///< centre of each section [rad]
  std::vector<double> attraction;      ///< attractor weight per section [0..1] (head); may be empty (base)
  std::vector<double> repulsion;       ///< repeller strength per section [>= 0, 0 = none]
  std::vector<double> forcelet;        ///< each section's contribution to the rate at `angle` [rad/s]
  double rate = 0.0;                   ///< the controller's dphi/dt [rad/s]
  double angle = 0.0;                  ///< the current angle phi [rad]
  double target = std::numeric_limits<double>::quiet_NaN();  ///< [rad], NaN = none
};

/// biovision_msgs/EgoMap: the short-term memory, egocentric (base_link, + = left).
struct EgoMapView
{
  double section_width = 0.0;             ///< [rad]
  std::vector<double> section_angles;     ///< section centres [rad]
  std::vector<double> obstacle_distance;  ///< [m], +Inf = nothing within range
  std::vector<double> confidence;         ///< [0..1]; may be empty (= 1)
  double max_range = 0.0;                 ///< [m]
};

/// One biovision_msgs/SalientRegion (boxes in full-resolution px).
struct RegionView
{
  unsigned rank = 0;
  cv::Rect box;
  double peak = 0.0;
  double inhibition = 0.0;  ///< inhibition of return [0..1]
};

/// One biovision_msgs/RecognizedObject (box in image px).
struct ObjectView
{
  std::string label;
  double score = 0.0;
  cv::Rect box;
};

/// An occupancy grid without ROS (biovision_common's, shared with PathPlot).
using GridView = biovision_common::GridView;
}  // namespace biovision_monitor
