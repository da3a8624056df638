#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "biovision_tasks/occupancy_map.hpp"
#include "biovision_tasks/task_parameters.hpp"

namespace biovision_tasks
{
/// Shortest paths over the long-term memory's obstacles, for excursions (thesis §5.3.3: "uses what was
/// gathered to move more efficiently"; the thesis gives no planner). A* on the 8-connected grid of the
/// OccupancyMap with the obstacles inflated by the robot's radius plus a margin, an extra cost near obstacles
/// (so paths keep clear of what the map has seen), then the path is shortened to the waypoints between which
/// the straight line stays free. When no path keeps that margin, a second pass keeps only `lethal_radius`
/// (exact distances, not whole-cell discs) and charges `margin_cost` per cell inside the margin — the
/// inscribed/inflated split of ROS costmaps (costmap_2d's inflation layer): a gap wider than the robot but
/// narrower than robot + 2 margins (a new box beside a bin in a corridor) is squeezed through instead of
/// leaving the base to drive straight at the goal. The base controller's attractor dynamics handle what the
/// map has not seen.
class GridPlanner
{
public:
  struct Options
  {
    int occupied_threshold = 40;  ///< LTM strength [0..100] that blocks
    double radius = 0.41;         ///< [m] robot radius + margin: the inflation
    double proximity_cost = 2.0;  ///< extra cost per cell for cells within `radius` beyond the inflation
    /// [m] the squeeze pass's hard clearance (cell centre to obstacle cell centre), (0, radius) to enable
    /// it; 0: no squeeze pass (a gap narrower than 2·radius has no path).
    double lethal_radius = 0.0;
    double margin_cost = 5.0;  ///< squeeze pass: extra cost per cell closer than `radius` to an obstacle
  };
  /// The options of the task parameters: radius = robot_radius + inflation_margin, lethal_radius =
  /// robot_radius + squeeze_margin (0 when that is not below the radius), occupied_threshold.
  static Options optionsFor(const TaskParameters& parameters);

  /// Plans from `start` to `goal` [m, map frame]. Returns the waypoints after the start, the last being the
  /// goal; empty when there is no path or either end is outside the map. A start inside the inflated
  /// obstacles (the robot brushed a wall) may leave them, never getting nearer an obstacle; a goal inside
  /// them has no path (inside the lethal radius, with the squeeze pass). `sight`, when given, receives the
  /// mask the waypoints were shortened against (lineOfSight's `blocked`: the inflated obstacles, or after a
  /// squeeze those minus the margin cells next to the path); it is emptied when there is no path.
  static std::vector<cv::Point2d> plan(const OccupancyMap& map, const cv::Point2d& start, const cv::Point2d& goal,
                                       const Options& options, cv::Mat1b* sight = nullptr);
  /// True when the straight segment a→b [m, map] crosses no inflated obstacle cell (`blocked` from
  /// OccupancyMap::inflatedObstacles); parts outside the map count as free, and so do the blocked cells
  /// the segment starts in (a robot inside the inflation may leave it).
  static bool lineOfSight(const OccupancyMap& map, const cv::Mat1b& blocked, const cv::Point2d& a,
                          const cv::Point2d& b);
};
}  // namespace biovision_tasks
