#include "biovision_monitor/monitor_panel.hpp"

#include <stdexcept>

#include "biovision_monitor/drawing.hpp"

namespace biovision_monitor
{
MonitorPanel::MonitorPanel(int columns, cv::Size tile_size) : columns_(columns), tile_size_(tile_size)
{
  if (columns < 1 || tile_size.width < 16 || tile_size.height < 16)
    throw std::invalid_argument("MonitorPanel: need columns >= 1 and tiles of at least 16 x 16 px");
}

cv::Rect MonitorPanel::tileRect(size_t index) const
{
  const int col = int(index % size_t(columns_)), row = int(index / size_t(columns_));
  return cv::Rect(col * (tile_size_.width + kGap), row * (tile_size_.height + kGap), tile_size_.width,
                  tile_size_.height);
}

cv::Size MonitorPanel::panelSize(size_t tiles) const
{
  const int cols = int(std::min<size_t>(std::max<size_t>(tiles, 1), size_t(columns_)));
  const int rows = int((std::max<size_t>(tiles, 1) + columns_ - 1) / columns_);
  return cv::Size(cols * tile_size_.width + (cols - 1) * kGap, rows * tile_size_.height + (rows - 1) * kGap);
}

cv::Mat MonitorPanel::compose(const std::vector<Tile>& tiles) const
{
  cv::Mat panel(panelSize(tiles.size()), CV_8UC3, cv::Scalar(30, 30, 30));
  for (size_t i = 0; i < tiles.size(); ++i)
  {
    const Tile& t = tiles[i];
    cv::Mat tile = panel(tileRect(i));  // drawn in place: the callers' pictures stay untouched
    if (t.image.empty())
      noDataTile(t.topic, tile_size_).copyTo(tile);
    else if (t.image.size() == tile_size_ && t.image.type() == CV_8UC3)
      t.image.copyTo(tile);
    else
      fitInto(t.image, tile_size_).copyTo(tile);
    drawTitle(tile, t.title + (t.stale ? "  (stale)" : ""));
  }
  return panel;
}
}  // namespace biovision_monitor
