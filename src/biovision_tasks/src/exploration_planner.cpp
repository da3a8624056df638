#include "biovision_tasks/exploration_planner.hpp"

#include <cmath>
#include <limits>

#include "biovision_tasks/grid_planner.hpp"

namespace biovision_tasks
{
ExplorationPlanner::ExplorationPlanner(const TaskParameters& parameters) : parameters_(parameters)
{
}

std::pair<int, int> ExplorationPlanner::cellOf(const cv::Point2d& p) const
{
  return {static_cast<int>(std::floor(p.x / parameters_.visit_cell)),
          static_cast<int>(std::floor(p.y / parameters_.visit_cell))};
}

void ExplorationPlanner::recordVisit(const Percept& percept)
{
  if (percept.pose_valid && last_time_ >= 0 && percept.time > last_time_)
    visits_[cellOf({percept.pose.x, percept.pose.y})] += std::min(percept.time - last_time_, 1.0);
  last_time_ = percept.time;
}

void ExplorationPlanner::markBoring(const cv::Point2d& point, double seconds)
{
  const auto [cx, cy] = cellOf(point);
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      visits_[{cx + dx, cy + dy}] += seconds;
}

double ExplorationPlanner::visits(const cv::Point2d& point) const
{
  const auto it = visits_.find(cellOf(point));
  return it == visits_.end() ? 0.0 : it->second;
}

bool ExplorationPlanner::nextGoal(const Percept& percept, const cv::Point2d& home, cv::Point2d& goal)
{
  if (!percept.pose_valid)
    return false;
  const cv::Point2d here(percept.pose.x, percept.pose.y);
  GridPlanner::Options o;
  o.occupied_threshold = parameters_.occupied_threshold;
  o.radius = parameters_.robot_radius + parameters_.inflation_margin;
  cv::Mat1b blocked;
  if (!percept.map.empty())
    blocked = percept.map.inflatedObstacles(o.occupied_threshold, o.radius);
  double best = std::numeric_limits<double>::infinity();
  bool found = false;
  for (int ring = 1; ring <= 2; ++ring)
    for (int k = 0; k < 16; ++k)
    {
      const double bearing = percept.pose.yaw + k * M_PI / 8;
      const cv::Point2d p = here + ring * parameters_.explore_step * cv::Point2d(std::cos(bearing), std::sin(bearing));
      int r, c;
      const bool in_map = !percept.map.empty() && percept.map.cellOf(p.x, p.y, r, c);
      if (in_map && blocked(r, c))
        continue;
      // Boredom of the goal and of the way there (the midpoint), a little cost for turning and distance.
      const double turn = std::abs(std::remainder(bearing - percept.pose.yaw, 2 * M_PI));
      const double score = visits(p) + 0.5 * visits((here + p) * 0.5) + 0.2 * turn + 0.2 * ring +
                           parameters_.home_range_cost * std::hypot(p.x - home.x, p.y - home.y);
      if (score >= best)
        continue;
      if (in_map && percept.map.cellOf(here.x, here.y, r, c) && GridPlanner::plan(percept.map, here, p, o).empty())
        continue;  // unreachable over what the map knows
      best = score;
      goal = p;
      found = true;
    }
  return found;
}
}  // namespace biovision_tasks
