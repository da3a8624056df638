#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_monitor/plot_inputs.hpp"

namespace biovision_monitor
{
/// The path a base drove, seen from above over the long-term memory map (thesis Figs. 5.8-5.10: the map
/// built on the way, the path, home and the objects), for run reports: map frame, metres, +x right and
/// +y up, one scale for both axes, a 1 m scale bar.
class PathPlot
{
public:
  struct Mark
  {
    cv::Point2d position;  ///< [m], map frame
    std::string label;     ///< drawn beside the mark
    cv::Scalar colour;     ///< BGR
    bool filled = true;    ///< a disc, else a ring (e.g. where the memory put an object vs where it is)
  };

  /// A CV_8UC3 image of `size`: the grid (when not empty; cell (0, 0)'s corner at `origin` [m], the
  /// occupancy shades of OccupancyGridPlot) and the path (polyline, start green, end red) and marks,
  /// fitted together with a 0.5 m margin. An empty grid and path give the marks alone (or a blank
  /// titled tile). Throws std::invalid_argument for a grid whose data does not match its size, a
  /// non-positive resolution of a non-empty grid, or a size smaller than 64 x 64 px.
  cv::Mat render(const GridView& grid, cv::Point2d origin, const std::vector<cv::Point2d>& path,
                 const std::vector<Mark>& marks, const std::string& title, cv::Size size) const;
};
}  // namespace biovision_monitor
