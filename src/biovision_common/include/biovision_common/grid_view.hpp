#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace biovision_common
{
/// An occupancy grid without ROS (the cells of a nav_msgs/OccupancyGrid or of the LTM): row-major from
/// cell (0, 0), +x along a row, +y from row to row; -1 unknown, 0 free … 100 occupied.
struct GridView
{
  int width = 0, height = 0;
  double resolution = 0.0;  ///< [m/cell]
  std::vector<signed char> data;

  /// The grid as a CV_8UC1 image of width x height px, +y up (image row 0 = the grid's last row): unknown
  /// (and values outside 0…100) grey 160, 0 white to 100 black. Throws std::invalid_argument when
  /// data.size() != width * height or a side is <= 0.
  cv::Mat toImage() const;
};
}  // namespace biovision_common
