#pragma once

#include <map>
#include <set>
#include <utility>

#include <opencv2/core.hpp>

#include "biovision_tasks/percept.hpp"
#include "biovision_tasks/task_parameters.hpp"

namespace biovision_tasks
{
/// Exploration (the exploration mode of thesis §5.3.3, whose strategy the thesis does not give), frontier-
/// first: cells of a coarse grid (visit_cell) that the camera has seen — within view_range, inside its view
/// (view_angle about Percept::view_yaw; all round when that is unknown) and not behind an LTM obstacle —
/// make up the coverage; the next goal is the nearest reachable frontier cell (seen, free, next to an unseen
/// cell not walled off; Yamauchi 1997), preferring its heading a little and cells near home. Once no frontier
/// is left, boredom: the time spent in each cell is counted and the goal is the candidate point (16 bearings ×
/// 1 and 2 × explore_step) that is least visited, free in the LTM and reachable over it (beyond its extent: in
/// sight over it), preferring the heading and points near home (home_range_cost). A goal the base could not
/// reach (it got trapped) is no frontier for a while and more boring for good (markUnreachable).
/// Deterministic: no random numbers. Bounded memory: beyond kMaxCells seen (or visited) cells, the half
/// farthest from the robot is forgotten (a long run in a big or unmapped world), and so are failures. Poses
/// that are not finite or farther than kMaxCoordinate from the origin are ignored.
class ExplorationPlanner
{
public:
  /// Seen or visited cells kept at most (~48 bytes each): at visit_cell 0.5 m, 6.5 ha of coverage.
  static constexpr size_t kMaxCells = size_t(1) << 18;
  /// [m] poses farther out are no localisation (the cell index would overflow).
  static constexpr double kMaxCoordinate = 1e6;

  explicit ExplorationPlanner(const TaskParameters& parameters);

  /// Accumulates the time spent at the robot's current cell since the last call and marks what the camera
  /// sees now as covered.
  void recordVisit(const Percept& percept);
  /// Picks a new goal [m, map frame]; false when no candidate is free (then the caller turns in place).
  bool nextGoal(const Percept& percept, const cv::Point2d& home, cv::Point2d& goal);
  /// A goal near `point` [m, map] the base could not reach (it got trapped) at `time` [s]: its cell and the 8
  /// round it are no frontier for frontier_retry_time · 2^(failures - 1) s and, for boredom, count as
  /// visited kUnreachableBoredom s more per failure. Why not for good: the trap is often the base's place,
  /// not the goal's (mission_eval report seeds 4, 6 and 42: wedged at one spot, every frontier of the room
  /// was struck off in 2.4 s each and the target's side never explored).
  void markUnreachable(const cv::Point2d& point, double time);
  /// [s of visits] added to the boredom of a cell per failure to reach it.
  static constexpr double kUnreachableBoredom = 60.0;
  /// Seconds spent in the cell of `point` (by the robot: failures to reach it are not counted).
  double visits(const cv::Point2d& point) const;
  /// visits() plus kUnreachableBoredom per failure to reach the cell of `point`.
  double boredom(const cv::Point2d& point) const;
  /// True when the cell of `point` has been seen (coverage).
  bool seen(const cv::Point2d& point) const;
  /// Number of cells seen (coverage), at most kMaxCells.
  size_t seenCells() const { return seen_.size(); }
  /// Number of cells with a visit time, at most kMaxCells.
  size_t visitedCells() const { return visits_.size(); }
  /// The best reachable frontier cell's centre [m, map] (the first choice of nextGoal); false when there is none
  /// (all seen, walled off, boring or unreachable) or view_range is 0.
  bool frontier(const Percept& percept, const cv::Point2d& home, cv::Point2d& goal) const;

private:
  using Cell = std::pair<int, int>;
  Cell cellOf(const cv::Point2d& p) const;
  cv::Point2d centreOf(const Cell& c) const;
  void markSeen(const Percept& percept);
  bool usable(const Percept& percept) const;
  bool excluded(const Cell& cell, double time) const;
  bool frontier(const Percept& percept, const cv::Point2d& home, const cv::Mat1b& blocked, cv::Point2d& goal) const;

  struct Failure
  {
    int count = 0;       ///< failures to reach the cell (capped at 16)
    double until = 0.0;  ///< [s] no frontier before this
  };

  TaskParameters parameters_;
  std::map<Cell, double> visits_;
  std::set<Cell> seen_;
  std::map<Cell, Failure> failures_;
  Cell robot_cell_{0, 0};  // of the last visit recorded
  double last_time_ = -1;
};
}  // namespace biovision_tasks
