#include "biovision_monitor/occupancy_grid_plot.hpp"

#include <stdexcept>
#include <string>

#include "biovision_monitor/drawing.hpp"

namespace biovision_monitor
{
cv::Mat OccupancyGridPlot::toImage(const GridView& grid)
{
  return grid.toImage();
}

cv::Mat OccupancyGridPlot::render(const GridView& grid, cv::Size size) const
{
  return fitInto(toImage(grid), size);
}
}  // namespace biovision_monitor
