#pragma once

// The one translation of the messages the monitor reads into the core's plain views (plot_inputs.hpp).

#include <cmath>
#include <vector>

#include <biovision_msgs/AttractorState.h>
#include <biovision_msgs/EgoMap.h>
#include <biovision_msgs/RecognizedObjectArray.h>
#include <biovision_msgs/SalientRegionArray.h>
#include <nav_msgs/OccupancyGrid.h>

#include "biovision_monitor/plot_inputs.hpp"

namespace biovision_monitor
{
template <typename T>
std::vector<double> toDoubles(const std::vector<T>& values)
{
  return std::vector<double>(values.begin(), values.end());
}

inline AttractorView toView(const biovision_msgs::AttractorState& m)
{
  AttractorView v;
  v.controller = m.controller;
  v.behaviour = m.behaviour;
  v.section_angles = toDoubles(m.section_angles);
  v.attraction = toDoubles(m.attraction);
  v.repulsion = toDoubles(m.repulsion);
  v.forcelet = toDoubles(m.forcelet);
  v.rate = m.rate;
  v.angle = m.angle;
  v.target = m.target;
  return v;
}

inline EgoMapView toView(const biovision_msgs::EgoMap& m)
{
  EgoMapView v;
  v.section_width = m.section_width;
  v.section_angles = toDoubles(m.section_angles);
  v.obstacle_distance = toDoubles(m.obstacle_distance);
  v.confidence = toDoubles(m.confidence);
  v.max_range = m.max_range;
  return v;
}

inline std::vector<RegionView> toView(const biovision_msgs::SalientRegionArray& m)
{
  std::vector<RegionView> regions;
  for (const auto& r : m.regions)
    regions.push_back({r.rank, cv::Rect(int(r.box.x_offset), int(r.box.y_offset), int(r.box.width), int(r.box.height)),
                       r.peak_saliency, r.inhibition});
  return regions;
}

inline std::vector<ObjectView> toView(const biovision_msgs::RecognizedObjectArray& m)
{
  std::vector<ObjectView> objects;
  for (const auto& o : m.objects)
    objects.push_back(
        {o.label, o.score, cv::Rect(int(o.box.x_offset), int(o.box.y_offset), int(o.box.width), int(o.box.height))});
  return objects;
}

inline GridView toView(const nav_msgs::OccupancyGrid& m)
{
  GridView v;
  v.width = int(m.info.width);
  v.height = int(m.info.height);
  v.resolution = m.info.resolution;
  v.data.assign(m.data.begin(), m.data.end());
  return v;
}
}  // namespace biovision_monitor
