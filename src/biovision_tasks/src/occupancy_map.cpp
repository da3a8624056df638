#include "biovision_tasks/occupancy_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace biovision_tasks
{
OccupancyMap::OccupancyMap(cv::Mat1b cells, double origin_x, double origin_y, double cell)
  : cells_(std::move(cells)), origin_x_(origin_x), origin_y_(origin_y), cell_(cell)
{
  if (!(cell > 0) || !std::isfinite(cell) || !std::isfinite(origin_x) || !std::isfinite(origin_y))
    throw std::invalid_argument("OccupancyMap: cell size must be > 0 and the origin finite");
}

bool OccupancyMap::cellOf(double x, double y, int& row, int& col) const
{
  if (cells_.empty() || !std::isfinite(x) || !std::isfinite(y))
    return false;
  col = static_cast<int>(std::floor((x - origin_x_) / cell_));
  row = static_cast<int>(std::floor((y - origin_y_) / cell_));
  return row >= 0 && col >= 0 && row < cells_.rows && col < cells_.cols;
}

cv::Rect OccupancyMap::cellsWithin(double x0, double y0, double x1, double y1) const
{
  if (cells_.empty() || !std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1))
    return {};
  const auto index = [this](double v, double origin, int size) {
    return static_cast<int>(std::clamp(std::floor((v - origin) / cell_), -1.0, static_cast<double>(size)));
  };
  const int c0 = std::max(0, index(std::min(x0, x1), origin_x_, cells_.cols));
  const int c1 = std::min(cells_.cols - 1, index(std::max(x0, x1), origin_x_, cells_.cols));
  const int r0 = std::max(0, index(std::min(y0, y1), origin_y_, cells_.rows));
  const int r1 = std::min(cells_.rows - 1, index(std::max(y0, y1), origin_y_, cells_.rows));
  if (c1 < c0 || r1 < r0)
    return {};
  return cv::Rect(c0, r0, c1 - c0 + 1, r1 - r0 + 1);
}

cv::Point2d OccupancyMap::centreOf(int row, int col) const
{
  return {origin_x_ + (col + 0.5) * cell_, origin_y_ + (row + 0.5) * cell_};
}

cv::Mat1b OccupancyMap::inflatedObstacles(int threshold, double radius) const
{
  cv::Mat1b blocked = (cells_ >= threshold) & (cells_ != kUnknown);
  const int r = static_cast<int>(std::ceil(radius / cell_));
  if (r > 0 && !blocked.empty())
    cv::dilate(blocked, blocked, cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * r + 1, 2 * r + 1}));
  return blocked;
}

cv::Mat1f OccupancyMap::obstacleDistance(int threshold) const
{
  if (cells_.empty())
    return {};
  const cv::Mat1b free = (cells_ < threshold) | (cells_ == kUnknown);
  cv::Mat1f distance;
  if (cv::countNonZero(free) == static_cast<int>(free.total()))
    distance = cv::Mat1f(cells_.size(), static_cast<float>(std::hypot(cells_.rows, cells_.cols)));
  else
    cv::distanceTransform(free, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  return distance * cell_;
}
}  // namespace biovision_tasks
