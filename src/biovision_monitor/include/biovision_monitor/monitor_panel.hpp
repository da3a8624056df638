#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace biovision_monitor
{
/// The robot monitoring panel of the thesis (Fig. 5.1, notes §6): tiles composed row by row into one
/// image, each titled; a tile without data says "no data on <topic>". Tiles are tile_size px, 2 px apart
/// on dark grey.
class MonitorPanel
{
public:
  static constexpr int kGap = 2;  ///< [px] between tiles

  /// One tile: its title, the topic it shows (for "no data on"), and the picture (empty = no data yet).
  /// `stale` adds "stale" to the title (data older than MonitorParameters::stale_after).
  struct Tile
  {
    std::string title;
    std::string topic;
    cv::Mat image;
    bool stale = false;
  };

  /// Throws std::invalid_argument when columns < 1 or a tile side < 16 px.
  MonitorPanel(int columns, cv::Size tile_size);

  /// The panel image (CV_8UC3) of `tiles`, in order, `columns` per row. Pictures of another size are
  /// fitted into their tile (aspect kept).
  cv::Mat compose(const std::vector<Tile>& tiles) const;

  /// Where tile `index` lies in a composed panel.
  cv::Rect tileRect(size_t index) const;
  /// The panel's size for `tiles` tiles.
  cv::Size panelSize(size_t tiles) const;

private:
  int columns_;
  cv::Size tile_size_;
};
}  // namespace biovision_monitor
