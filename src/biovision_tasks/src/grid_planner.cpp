#include "biovision_tasks/grid_planner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include <opencv2/imgproc.hpp>

namespace biovision_tasks
{
namespace
{
// True when the straight segment between two cells crosses no blocked cell.
bool lineFree(const cv::Mat1b& blocked, cv::Point a, cv::Point b)
{
  cv::LineIterator it(blocked, a, b, 8);
  for (int i = 0; i < it.count; ++i, ++it)
    if (**it)
      return false;
  return true;
}
}  // namespace

bool GridPlanner::lineOfSight(const OccupancyMap& map, const cv::Mat1b& blocked, const cv::Point2d& a,
                              const cv::Point2d& b)
{
  const double length = std::hypot(b.x - a.x, b.y - a.y);
  const int n = std::max(1, static_cast<int>(std::ceil(length / (map.cellSize() / 2))));
  bool leaving = true;  // a start inside the inflation (the robot brushed a wall) may leave through it
  for (int i = 0; i <= n; ++i)
  {
    const cv::Point2d p = a + (b - a) * (static_cast<double>(i) / n);
    int r, c;
    const bool hit = map.cellOf(p.x, p.y, r, c) && blocked(r, c);
    if (hit && !leaving)
      return false;
    leaving = leaving && hit;
  }
  return true;
}

std::vector<cv::Point2d> GridPlanner::plan(const OccupancyMap& map, const cv::Point2d& start, const cv::Point2d& goal,
                                           const Options& options)
{
  int sr, sc, gr, gc;
  if (!map.cellOf(start.x, start.y, sr, sc) || !map.cellOf(goal.x, goal.y, gr, gc))
    return {};
  cv::Mat1b blocked = map.inflatedObstacles(options.occupied_threshold, options.radius);
  if (blocked(gr, gc))
    return {};
  // Near-obstacle cost: cells within one more radius of the inflated obstacles.
  cv::Mat1b near;
  const int r = std::max(1, static_cast<int>(std::ceil(options.radius / map.cellSize())));
  cv::dilate(blocked, near, cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * r + 1, 2 * r + 1}));
  // The start may be inside the inflation: let the robot leave through cells that are not true obstacles.
  cv::Mat1b passable = ~blocked;
  if (blocked(sr, sc))
  {
    const cv::Mat1b hard = (map.cells() >= options.occupied_threshold) & (map.cells() != OccupancyMap::kUnknown);
    passable = ~hard;
  }

  const int rows = blocked.rows, cols = blocked.cols;
  const auto index = [cols](int row, int col) { return row * cols + col; };
  std::vector<double> cost(static_cast<size_t>(rows) * cols, std::numeric_limits<double>::infinity());
  std::vector<int> parent(cost.size(), -1);
  using Node = std::pair<double, int>;
  std::priority_queue<Node, std::vector<Node>, std::greater<Node>> open;
  const auto heuristic = [&](int row, int col) {
    const double dr = std::abs(row - gr), dc = std::abs(col - gc);
    return std::max(dr, dc) + (std::sqrt(2.0) - 1) * std::min(dr, dc);
  };
  cost[index(sr, sc)] = 0;
  open.push({heuristic(sr, sc), index(sr, sc)});
  const int goal_index = index(gr, gc);
  while (!open.empty())
  {
    const auto [f, i] = open.top();
    open.pop();
    if (i == goal_index)
      break;
    const int row = i / cols, col = i % cols;
    if (f - heuristic(row, col) > cost[i] + 1e-9)
      continue;  // stale entry
    // Once out of the inflation, stay out of it.
    const bool escaping = blocked(row, col) != 0;
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc)
      {
        const int nr = row + dr, nc = col + dc;
        if ((dr == 0 && dc == 0) || nr < 0 || nc < 0 || nr >= rows || nc >= cols)
          continue;
        if (!(escaping ? passable(nr, nc) : !blocked(nr, nc)))
          continue;
        const double step = (dr != 0 && dc != 0 ? std::sqrt(2.0) : 1.0) + (near(nr, nc) ? options.proximity_cost : 0);
        const int j = index(nr, nc);
        if (cost[i] + step < cost[j])
        {
          cost[j] = cost[i] + step;
          parent[j] = i;
          open.push({cost[j] + heuristic(nr, nc), j});
        }
      }
  }
  if (!std::isfinite(cost[goal_index]))
    return {};

  std::vector<cv::Point> cells;
  for (int i = goal_index; i != -1; i = parent[i])
    cells.emplace_back(i % cols, i / cols);
  std::reverse(cells.begin(), cells.end());
  // Shorten: from each kept cell, jump to the farthest cell still in straight free sight.
  std::vector<cv::Point2d> waypoints;
  size_t from = 0;
  while (from + 1 < cells.size())
  {
    size_t to = from + 1;
    for (size_t k = cells.size() - 1; k > from + 1; --k)
      if (lineFree(blocked, cells[from], cells[k]))
      {
        to = k;
        break;
      }
    waypoints.push_back(map.centreOf(cells[to].y, cells[to].x));
    from = to;
  }
  if (waypoints.empty())
    waypoints.push_back(map.centreOf(gr, gc));
  waypoints.back() = goal;  // end exactly at the goal, not its cell's centre
  return waypoints;
}
}  // namespace biovision_tasks
