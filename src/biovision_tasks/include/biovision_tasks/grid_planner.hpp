#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "biovision_tasks/occupancy_map.hpp"

namespace biovision_tasks
{
/// Shortest paths over the long-term memory's obstacles, for excursions (thesis §5.3.3: "uses what was
/// gathered to move more efficiently"; the thesis gives no planner). A* on the 8-connected grid of the
/// OccupancyMap with the obstacles inflated by the robot's radius, an extra cost near obstacles (so paths
/// keep clear of what the map has seen), then the path is shortened to the waypoints between which the
/// straight line stays free. The base controller's attractor dynamics handle what the map has not seen.
class GridPlanner
{
public:
  struct Options
  {
    int occupied_threshold = 40;  ///< LTM strength [0..100] that blocks
    double radius = 0.41;         ///< [m] robot radius + margin: the inflation
    double proximity_cost = 2.0;  ///< extra cost per cell for cells within `radius` beyond the inflation
  };

  /// Plans from `start` to `goal` [m, map frame]. Returns the waypoints after the start, the last being the
  /// goal; empty when there is no path or either end is outside the map. A start inside the inflated
  /// obstacles (the robot brushed a wall) may leave through them; a goal inside them has no path.
  static std::vector<cv::Point2d> plan(const OccupancyMap& map, const cv::Point2d& start, const cv::Point2d& goal,
                                       const Options& options);
  /// True when the straight segment a→b [m, map] crosses no inflated obstacle cell (`blocked` from
  /// OccupancyMap::inflatedObstacles); parts outside the map count as free, and so do the blocked cells
  /// the segment starts in (a robot inside the inflation may leave it).
  static bool lineOfSight(const OccupancyMap& map, const cv::Mat1b& blocked, const cv::Point2d& a,
                          const cv::Point2d& b);
};
}  // namespace biovision_tasks
