#pragma once

#include <map>
#include <utility>

#include <opencv2/core.hpp>

#include "biovision_tasks/percept.hpp"
#include "biovision_tasks/task_parameters.hpp"

namespace biovision_tasks
{
/// Boredom-driven exploration (the exploration mode of thesis §5.3.3, whose strategy the thesis does not
/// give): the robot counts the time it spends in each cell of a coarse grid (visit_cell) and picks as its
/// next goal the candidate point (16 bearings × 1 and 2 × explore_step around it) that is least visited,
/// free in the LTM and reachable over it, preferring its current heading a little and points near home
/// (home_range_cost), so that it covers the area round home first. A point the base could
/// not reach (it got trapped) becomes "boring" so another is picked. Deterministic: no random numbers.
class ExplorationPlanner
{
public:
  explicit ExplorationPlanner(const TaskParameters& parameters);

  /// Accumulates the time spent at the robot's current cell since the last call.
  void recordVisit(const Percept& percept);
  /// Picks a new goal [m, map frame]; false when no candidate is free (then the caller turns in place).
  bool nextGoal(const Percept& percept, const cv::Point2d& home, cv::Point2d& goal);
  /// Marks the area around `point` as visited for `seconds` (an unreachable goal).
  void markBoring(const cv::Point2d& point, double seconds);
  /// Seconds spent in the cell of `point`.
  double visits(const cv::Point2d& point) const;

private:
  std::pair<int, int> cellOf(const cv::Point2d& p) const;

  TaskParameters parameters_;
  std::map<std::pair<int, int>, double> visits_;
  double last_time_ = -1;
};
}  // namespace biovision_tasks
