#pragma once

#include <opencv2/core.hpp>

namespace biovision_hri
{
/// L2-normalised blocks of pooled complex cells at every pixel of an image (or pyramid level), for one
/// pooling cell size: the dense form of the window descriptor, computed once per image and slid.
///
/// `data` is rows x cols x `channels` CV_32F (one cv::Mat with `channels` channels): at (y, x) the
/// block whose top-left cell starts at pixel (x, y), channels ordered cell row, cell column,
/// orientation. Only positions whose block lies inside the image exist: rows = H - block_cells*cell + 1.
struct BlockMap
{
  cv::Mat data;
  int cell_size = 0;  ///< pooling cell side [px of the level]
  int channels = 0;   ///< FeatureLayout::blockLength()

  const float* at(int y, int x) const { return data.ptr<float>(y) + static_cast<size_t>(x) * channels; }
  bool empty() const { return data.empty(); }
};
}  // namespace biovision_hri
