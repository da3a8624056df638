#include "biovision_tasks/exploration_planner.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <utility>
#include <vector>

#include "biovision_tasks/grid_planner.hpp"

namespace biovision_tasks
{
ExplorationPlanner::ExplorationPlanner(const TaskParameters& parameters) : parameters_(parameters)
{
}

namespace
{
// A cell of the LTM holding an obstacle (not merely unknown): what blocks the view and walls off a frontier.
bool obstacleAt(const OccupancyMap& map, const cv::Point2d& p, int threshold)
{
  int r, c;
  if (map.empty() || !map.cellOf(p.x, p.y, r, c))
    return false;
  const unsigned char v = map.cells()(r, c);
  return v != OccupancyMap::kUnknown && v >= threshold;
}

// True when the straight segment a-b passes no LTM obstacle (sampled at a quarter cell).
bool inSight(const OccupancyMap& map, const cv::Point2d& a, const cv::Point2d& b, int threshold)
{
  if (map.empty())
    return true;
  const double length = std::hypot(b.x - a.x, b.y - a.y);
  const int n = std::max(1, static_cast<int>(std::ceil(length / (map.cellSize() / 4))));
  for (int i = 1; i <= n; ++i)
    if (obstacleAt(map, a + (b - a) * (static_cast<double>(i) / n), threshold))
      return false;
  return true;
}

const std::pair<int, int>& key(const std::pair<int, int>& c)
{
  return c;
}
template <typename Value>
const std::pair<int, int>& key(const std::pair<const std::pair<int, int>, Value>& c)
{
  return c.first;
}

// Keeps the half of `cells` (a std::set or std::map over (x, y) cell indices) nearest to `here` once it holds
// more than `limit`.
template <typename Cells>
void forgetFarthest(Cells& cells, const std::pair<int, int>& here, size_t limit)
{
  if (cells.size() <= limit)
    return;
  auto far = [&here](const std::pair<int, int>& c) {
    const double dx = static_cast<double>(c.first) - here.first, dy = static_cast<double>(c.second) - here.second;
    return dx * dx + dy * dy;
  };
  std::vector<double> distances;
  distances.reserve(cells.size());
  for (const auto& c : cells)
    distances.push_back(far(key(c)));
  auto middle = distances.begin() + static_cast<std::ptrdiff_t>(limit / 2);
  std::nth_element(distances.begin(), middle, distances.end());
  const double cut = *middle;
  for (auto it = cells.begin(); it != cells.end();)
    it = far(key(*it)) >= cut ? cells.erase(it) : std::next(it);
}
}  // namespace

ExplorationPlanner::Cell ExplorationPlanner::cellOf(const cv::Point2d& p) const
{
  return {static_cast<int>(std::floor(p.x / parameters_.visit_cell)),
          static_cast<int>(std::floor(p.y / parameters_.visit_cell))};
}

cv::Point2d ExplorationPlanner::centreOf(const Cell& c) const
{
  return {(c.first + 0.5) * parameters_.visit_cell, (c.second + 0.5) * parameters_.visit_cell};
}

bool ExplorationPlanner::usable(const Percept& percept) const
{
  return percept.pose_valid && std::abs(percept.pose.x) <= kMaxCoordinate &&
         std::abs(percept.pose.y) <= kMaxCoordinate && std::isfinite(percept.pose.yaw);
}

void ExplorationPlanner::recordVisit(const Percept& percept)
{
  if (usable(percept) && last_time_ >= 0 && percept.time > last_time_)
  {
    const Cell here = cellOf({percept.pose.x, percept.pose.y});
    visits_[here] += std::min(percept.time - last_time_, 1.0);
    forgetFarthest(visits_, here, kMaxCells);
    robot_cell_ = here;
  }
  last_time_ = percept.time;
  markSeen(percept);
}

void ExplorationPlanner::markSeen(const Percept& percept)
{
  if (!usable(percept) || !(parameters_.view_range > 0))
    return;
  const cv::Point2d here(percept.pose.x, percept.pose.y);
  seen_.insert(cellOf(here));
  const bool directed = std::isfinite(percept.view_yaw);
  const double fan = directed ? parameters_.view_angle : 2 * M_PI;
  const double centre = directed ? percept.view_yaw : 0.0;
  // Rays half a coverage cell apart at the far end; steps of half an LTM cell along each (no wall is
  // stepped over), up to an LTM obstacle.
  const double spacing = parameters_.visit_cell / 2;
  const double step = percept.map.empty() ? spacing : std::min(spacing, percept.map.cellSize() / 2);
  const int rays = std::max(2, static_cast<int>(std::ceil(fan * parameters_.view_range / spacing)));
  const int steps = static_cast<int>(std::ceil(parameters_.view_range / step));
  for (int k = 0; k <= rays; ++k)
  {
    const double a = centre - fan / 2 + fan * k / rays;
    const cv::Point2d direction(std::cos(a), std::sin(a));
    Cell last = cellOf(here);  // steps are finer than the coverage cells: insert each cell once per ray
    for (int i = 1; i <= steps; ++i)
    {
      const cv::Point2d p = here + direction * std::min(i * step, parameters_.view_range);
      if (obstacleAt(percept.map, p, parameters_.occupied_threshold))
        break;
      const Cell c = cellOf(p);
      if (c != last)
        seen_.insert(c);
      last = c;
    }
  }
  forgetFarthest(seen_, cellOf(here), kMaxCells);
}

bool ExplorationPlanner::seen(const cv::Point2d& point) const
{
  if (!(std::abs(point.x) <= kMaxCoordinate && std::abs(point.y) <= kMaxCoordinate))
    return false;
  return seen_.count(cellOf(point)) > 0;
}

bool ExplorationPlanner::frontier(const Percept& percept, const cv::Point2d& home, cv::Point2d& goal) const
{
  cv::Mat1b blocked;
  if (!percept.map.empty())
  {
    const GridPlanner::Options o = GridPlanner::optionsFor(parameters_);
    blocked = percept.map.inflatedObstacles(o.occupied_threshold, o.radius);
  }
  return frontier(percept, home, blocked, goal);
}

bool ExplorationPlanner::frontier(const Percept& percept, const cv::Point2d& home, const cv::Mat1b& blocked,
                                  cv::Point2d& goal) const
{
  if (!usable(percept) || !(parameters_.view_range > 0))
    return false;
  const cv::Point2d here(percept.pose.x, percept.pose.y);
  const int threshold = parameters_.occupied_threshold;
  std::vector<std::pair<double, cv::Point2d>> frontiers;
  for (const Cell& c : seen_)
  {
    const cv::Point2d p = centreOf(c);
    const double distance = std::hypot(p.x - here.x, p.y - here.y);
    // Too near to be worth a drive (the look round reveals it); 30 s spent there; or struck off for now (a goal
    // the base could not reach, markUnreachable).
    if (distance < 2 * parameters_.visit_cell || visits(p) >= 30.0 || excluded(c, percept.time))
      continue;
    int r, col;
    if (!blocked.empty() && percept.map.cellOf(p.x, p.y, r, col) && blocked(r, col))
      continue;
    bool frontier = false;
    for (const Cell& n : {Cell{c.first + 1, c.second}, Cell{c.first - 1, c.second}, Cell{c.first, c.second + 1},
                          Cell{c.first, c.second - 1}})
      if (!seen_.count(n) && inSight(percept.map, p, centreOf(n), threshold))
        frontier = true;
    if (!frontier)
      continue;
    const double turn = std::abs(std::remainder(std::atan2(p.y - here.y, p.x - here.x) - percept.pose.yaw, 2 * M_PI));
    // Metres of driving, a little for turning and for boredom, and home_range_cost per metre from home.
    const double score = distance + 0.3 * turn + 0.1 * visits(p) +
                         parameters_.home_range_cost * std::hypot(p.x - home.x, p.y - home.y);
    frontiers.emplace_back(score, p);
  }
  std::sort(frontiers.begin(), frontiers.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  const GridPlanner::Options o = GridPlanner::optionsFor(parameters_);
  int r, c;
  const bool start_in_map = !percept.map.empty() && percept.map.cellOf(here.x, here.y, r, c);
  // Planning is the expensive part: only the best few are checked for a way there.
  for (size_t k = 0; k < frontiers.size() && k < 8; ++k)
  {
    const cv::Point2d& p = frontiers[k].second;
    if (start_in_map && percept.map.cellOf(p.x, p.y, r, c) && GridPlanner::plan(percept.map, here, p, o).empty())
      continue;
    goal = p;
    return true;
  }
  return false;
}

void ExplorationPlanner::markUnreachable(const cv::Point2d& point, double time)
{
  if (!(std::abs(point.x) <= kMaxCoordinate && std::abs(point.y) <= kMaxCoordinate) || !std::isfinite(time))
    return;
  const auto [cx, cy] = cellOf(point);
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
    {
      Failure& f = failures_[{cx + dx, cy + dy}];
      f.count = std::min(f.count + 1, 16);
      // Doubling with each failure: a place the base cannot reach from anywhere is soon left alone.
      f.until = time + parameters_.frontier_retry_time * std::ldexp(1.0, f.count - 1);
    }
  // Round the robot, as the visits: the failures farthest from it matter least.
  forgetFarthest(failures_, robot_cell_, kMaxCells);
}

bool ExplorationPlanner::excluded(const Cell& cell, double time) const
{
  const auto it = failures_.find(cell);
  return it != failures_.end() && time < it->second.until;
}

double ExplorationPlanner::boredom(const cv::Point2d& point) const
{
  const double v = visits(point);
  if (!(std::abs(point.x) <= kMaxCoordinate && std::abs(point.y) <= kMaxCoordinate))
    return v;
  const auto it = failures_.find(cellOf(point));
  return it == failures_.end() ? v : v + kUnreachableBoredom * it->second.count;
}

double ExplorationPlanner::visits(const cv::Point2d& point) const
{
  if (!(std::abs(point.x) <= kMaxCoordinate && std::abs(point.y) <= kMaxCoordinate))
    return 0.0;
  const auto it = visits_.find(cellOf(point));
  return it == visits_.end() ? 0.0 : it->second;
}

bool ExplorationPlanner::nextGoal(const Percept& percept, const cv::Point2d& home, cv::Point2d& goal)
{
  if (!usable(percept))
    return false;
  const cv::Point2d here(percept.pose.x, percept.pose.y);
  const GridPlanner::Options o = GridPlanner::optionsFor(parameters_);
  cv::Mat1b blocked;
  if (!percept.map.empty())
    blocked = percept.map.inflatedObstacles(o.occupied_threshold, o.radius);
  if (frontier(percept, home, blocked, goal))
    return true;
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
      // Beyond the map's extent nothing blocks the goal itself, but the way there must not cross a known
      // obstacle: make demo's corridor got goals 1 m behind its walls, which no plan reached.
      if (!in_map && !inSight(percept.map, here, p, parameters_.occupied_threshold))
        continue;
      // Boredom of the goal and of the way there (the midpoint), a little cost for turning and distance.
      const double turn = std::abs(std::remainder(bearing - percept.pose.yaw, 2 * M_PI));
      const double score = boredom(p) + 0.5 * boredom((here + p) * 0.5) + 0.2 * turn + 0.2 * ring +
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
