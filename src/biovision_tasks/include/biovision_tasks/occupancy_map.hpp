#pragma once

#include <opencv2/core.hpp>

namespace biovision_tasks
{
/// A 2-D obstacle map in the `map` frame, as the long-term memory publishes it (nav_msgs/OccupancyGrid
/// layout): cell (r, c) covers x in [origin_x + c·cell, +cell), y in [origin_y + r·cell, +cell).
/// Values: 0..100 = obstacle strength (thesis §5.3.2 scaled to 0..100), kUnknown = never observed.
class OccupancyMap
{
public:
  static constexpr unsigned char kUnknown = 255;

  OccupancyMap() = default;
  /// cells: CV_8UC1; cell [m] > 0. Throws std::invalid_argument otherwise.
  OccupancyMap(cv::Mat1b cells, double origin_x, double origin_y, double cell);

  bool empty() const { return cells_.empty(); }
  const cv::Mat1b& cells() const { return cells_; }
  double originX() const { return origin_x_; }
  double originY() const { return origin_y_; }
  double cellSize() const { return cell_; }

  /// The cell containing (x, y) [m]; false when outside the map.
  bool cellOf(double x, double y, int& row, int& col) const;
  /// The cells overlapping the box [x0, x1] x [y0, y1] [m] (corners in any order), clipped to the map: x
  /// along columns, y along rows; empty when the box misses the map or a bound is not finite (clamped
  /// before the int conversion, so a pose far outside cannot overflow it).
  cv::Rect cellsWithin(double x0, double y0, double x1, double y1) const;
  /// Centre of a cell [m].
  cv::Point2d centreOf(int row, int col) const;
  /// Obstacles at strength >= threshold [0..100] grown by `radius` [m] (the robot's radius plus a
  /// margin): 255 where the robot's centre may not go, else 0. Unknown cells are free (exploration is
  /// optimistic; the base's STM avoids what the map has not seen).
  cv::Mat1b inflatedObstacles(int threshold, double radius) const;
  /// Euclidean distance [m] from each cell's centre to the nearest obstacle cell's centre (strength >=
  /// threshold, unknown = free), CV_32FC1 of the map's size; large (the map's diagonal) with no obstacle.
  /// Exact, unlike inflatedObstacles' whole-cell discs: GridPlanner's squeeze pass needs the true gap.
  cv::Mat1f obstacleDistance(int threshold) const;

private:
  cv::Mat1b cells_;
  double origin_x_ = 0, origin_y_ = 0, cell_ = 0.1;
};
}  // namespace biovision_tasks
