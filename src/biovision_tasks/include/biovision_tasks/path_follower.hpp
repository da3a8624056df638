#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "biovision_tasks/percept.hpp"
#include "biovision_tasks/task_parameters.hpp"

namespace biovision_tasks
{
/// Hands the base controller one waypoint at a time on the way to a goal: plans over the long-term memory
/// (GridPlanner, inflated by robot_radius + inflation_margin), replans every replan_period (the LTM
/// changes as the robot drives) or when asked (the base got trapped), drops the waypoints passed
/// (waypoint_tolerance) once the next one is in straight free sight over the map (so no corner is cut). With no map or no path it heads straight for the goal and leaves the obstacles
/// to the base's attractor dynamics. Used by the excursions (GoToTask) and the exploration (SearchTask).
class PathFollower
{
public:
  explicit PathFollower(const TaskParameters& parameters);

  /// A new goal [m, map]; `plan` false: straight, never over the map (micro-task "forward").
  void setGoal(const cv::Point2d& goal, bool plan = true);
  /// Follows `route` [m, map] as it is, its last point the goal: no planning, no replanning (blockAhead()
  /// keeps it); waypoints are passed within waypoint_tolerance. A later setGoal() plans again.
  void followRoute(const std::vector<cv::Point2d>& route);
  bool followingRoute() const { return route_; }
  /// Replans at the next waypoint() call.
  void replanSoon() { planned_at_ = -1e18; }
  /// The base is trapped: what stops it is in its STM but not (yet) in the LTM, so the plan keeps leading into
  /// it. Marks a disc of robot_radius 0.7 m from the base towards the current waypoint (its heading when there
  /// is none) as an obstacle in every later plan of this goal (a new goal forgets them) and replans.
  void blockAhead(const Percept& percept);
  /// The waypoint to drive to now [m, map].
  cv::Point2d waypoint(const Percept& percept);
  const std::vector<cv::Point2d>& waypoints() const { return waypoints_; }
  const cv::Point2d& goal() const { return goal_; }

private:
  TaskParameters parameters_;
  cv::Point2d goal_;
  bool plan_ = true;
  bool route_ = false;  ///< followRoute(): the waypoints are fixed
  std::vector<cv::Point2d> waypoints_;
  std::vector<cv::Point2d> blocked_points_;  ///< blockAhead()'s discs [m, map]
  cv::Mat1b blocked_;                        ///< the inflated obstacles of the last plan (empty: no map)
  double planned_at_ = -1e18;
};
}  // namespace biovision_tasks
