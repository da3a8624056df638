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

namespace
{
// A* over the 8-connected grid from (sr, sc) to (gr, gc) avoiding `blocked`, each step costing its length plus
// `extra` of the cell entered. A start inside `blocked` leaves it never getting nearer an obstacle (`distance`
// from OccupancyMap::obstacleDistance never shrinking; read only then, so it may be empty for a start
// outside): letting it move freely inside, as before, gave paths that ran along the inflation band hugging
// the obstacle the robot stood next to (the demo's base pressed against the new crate it was trapped by).
// Cells of the path, start first; empty when there is none.
std::vector<cv::Point> searchGrid(const cv::Mat1b& blocked, const cv::Mat1f& distance, const cv::Mat1f& extra, int sr,
                                  int sc, int gr, int gc)
{
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
    const float clearance = escaping ? distance(row, col) : 0.0f;
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc)
      {
        const int nr = row + dr, nc = col + dc;
        if ((dr == 0 && dc == 0) || nr < 0 || nc < 0 || nr >= rows || nc >= cols)
          continue;
        if (blocked(nr, nc) && !(escaping && distance(nr, nc) >= clearance))
          continue;
        const double step = (dr != 0 && dc != 0 ? std::sqrt(2.0) : 1.0) + extra(nr, nc);
        const int j = index(nr, nc);
        if (cost[i] + step < cost[j])
        {
          cost[j] = cost[i] + step;
          parent[j] = i;
          open.push({cost[j] + heuristic(nr, nc), j});
        }
      }
  }
  std::vector<cv::Point> cells;
  if (!std::isfinite(cost[goal_index]))
    return cells;
  for (int i = goal_index; i != -1; i = parent[i])
    cells.emplace_back(i % cols, i / cols);
  std::reverse(cells.begin(), cells.end());
  return cells;
}
}  // namespace

GridPlanner::Options GridPlanner::optionsFor(const TaskParameters& parameters)
{
  Options o;
  o.occupied_threshold = parameters.occupied_threshold;
  o.radius = parameters.robot_radius + parameters.inflation_margin;
  const double lethal = parameters.robot_radius + parameters.squeeze_margin;
  o.lethal_radius = lethal < o.radius ? lethal : 0.0;
  return o;
}

std::vector<cv::Point2d> GridPlanner::plan(const OccupancyMap& map, const cv::Point2d& start, const cv::Point2d& goal,
                                           const Options& options, cv::Mat1b* sight)
{
  if (sight)
    sight->release();
  int sr, sc, gr, gc;
  if (!map.cellOf(start.x, start.y, sr, sc) || !map.cellOf(goal.x, goal.y, gr, gc))
    return {};
  const cv::Mat1b inflated = map.inflatedObstacles(options.occupied_threshold, options.radius);
  // The distance transform only when it is read (a start in the inflation, the squeeze pass): the
  // exploration planner plans dozens of times per goal over the same map.
  cv::Mat1f distance;
  const auto distances = [&]() -> const cv::Mat1f& {
    if (distance.empty())
      distance = map.obstacleDistance(options.occupied_threshold);
    return distance;
  };
  // Near-obstacle cost: cells within one more radius of the inflated obstacles.
  cv::Mat1b near;
  const int r = std::max(1, static_cast<int>(std::ceil(options.radius / map.cellSize())));
  cv::dilate(inflated, near, cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * r + 1, 2 * r + 1}));
  cv::Mat1f extra;
  near.convertTo(extra, CV_32F, options.proximity_cost / 255.0);

  std::vector<cv::Point> cells;
  cv::Mat1b shorten = inflated;
  if (!inflated(gr, gc))
    cells = searchGrid(inflated, inflated(sr, sc) ? distances() : distance, extra, sr, sc, gr, gc);
  if (cells.empty() && options.lethal_radius > 0 && options.lethal_radius < options.radius)
  {
    // Squeeze: only the lethal radius blocks; the margin costs margin_cost a cell.
    const cv::Mat1b lethal = distances() < static_cast<float>(options.lethal_radius);
    if (lethal(gr, gc))
      return {};
    const cv::Mat1b margin = distances() < static_cast<float>(options.radius);
    cv::Mat1f margin_extra;
    margin.convertTo(margin_extra, CV_32F, options.margin_cost / 255.0);
    cells = searchGrid(lethal, distances(), extra + margin_extra, sr, sc, gr, gc);
    if (!cells.empty())
    {
      // Shortcuts may cross the margin only where the path itself does (next to its cells), not hug
      // every obstacle on the way.
      cv::Mat1b corridor(inflated.size(), uchar(0));
      for (const cv::Point& c : cells)
        corridor(c) = 255;
      cv::dilate(corridor, corridor, cv::Mat());
      shorten = lethal | (inflated & ~corridor);
    }
  }
  if (cells.empty())
    return {};

  // Shorten: from each kept cell, jump to the farthest cell still in straight free sight.
  std::vector<cv::Point2d> waypoints;
  size_t from = 0;
  while (from + 1 < cells.size())
  {
    size_t to = from + 1;
    for (size_t k = cells.size() - 1; k > from + 1; --k)
      if (lineFree(shorten, cells[from], cells[k]))
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
  if (sight)
    *sight = shorten;
  return waypoints;
}
}  // namespace biovision_tasks
