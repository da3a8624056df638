#include "biovision_monitor/occupancy_grid_plot.hpp"

#include <stdexcept>
#include <string>

#include "biovision_monitor/drawing.hpp"

namespace biovision_monitor
{
cv::Mat OccupancyGridPlot::toImage(const GridView& grid)
{
  if (grid.width <= 0 || grid.height <= 0 || grid.data.size() != size_t(grid.width) * size_t(grid.height))
    throw std::invalid_argument("OccupancyGridPlot: a " + std::to_string(grid.width) + " x " +
                                std::to_string(grid.height) + " grid needs that many cells, got " +
                                std::to_string(grid.data.size()));
  cv::Mat image(grid.height, grid.width, CV_8UC1);
  for (int r = 0; r < grid.height; ++r)
  {
    const signed char* in = grid.data.data() + size_t(r) * grid.width;
    uchar* out = image.ptr<uchar>(grid.height - 1 - r);
    for (int c = 0; c < grid.width; ++c)
    {
      const int v = in[c];
      out[c] = (v < 0 || v > 100) ? 160 : uchar(255 - v * 255 / 100);
    }
  }
  return image;
}

cv::Mat OccupancyGridPlot::render(const GridView& grid, cv::Size size) const
{
  return fitInto(toImage(grid), size);
}
}  // namespace biovision_monitor
