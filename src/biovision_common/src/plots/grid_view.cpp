#include "biovision_common/grid_view.hpp"

#include <stdexcept>
#include <string>

namespace biovision_common
{
cv::Mat GridView::toImage() const
{
  if (width <= 0 || height <= 0 || data.size() != size_t(width) * size_t(height))
    throw std::invalid_argument("GridView: a " + std::to_string(width) + " x " + std::to_string(height) +
                                " grid needs that many cells, got " + std::to_string(data.size()));
  cv::Mat image(height, width, CV_8UC1);
  for (int r = 0; r < height; ++r)
  {
    const signed char* in = data.data() + size_t(r) * width;
    uchar* out = image.ptr<uchar>(height - 1 - r);
    for (int c = 0; c < width; ++c)
    {
      const int v = in[c];
      out[c] = (v < 0 || v > 100) ? 160 : uchar(255 - v * 255 / 100);
    }
  }
  return image;
}
}  // namespace biovision_common
