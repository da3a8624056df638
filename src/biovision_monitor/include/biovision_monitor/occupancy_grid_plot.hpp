#pragma once

#include <opencv2/core.hpp>

#include "biovision_monitor/plot_inputs.hpp"

namespace biovision_monitor
{
/// The long-term memory map (nav_msgs/OccupancyGrid, thesis Fig. 5.4) as an image: unknown cells grey,
/// 0 (free) white to 100 (occupied, strongest) black, +y of the map up (grid row 0 at the bottom), cells
/// scaled up without smoothing to fill the tile.
class OccupancyGridPlot
{
public:
  /// The grid as a CV_8UC1 image of width x height px (row 0 = the map's top = the grid's last row).
  /// Throws std::invalid_argument when data.size() != width * height or a side is <= 0.
  static cv::Mat toImage(const GridView& grid);

  /// toImage() fitted into a CV_8UC3 tile of `size`.
  cv::Mat render(const GridView& grid, cv::Size size) const;
};
}  // namespace biovision_monitor
