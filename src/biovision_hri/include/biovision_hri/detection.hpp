#pragma once

#include <opencv2/core.hpp>

namespace biovision_hri
{
/// One detection window in image coordinates.
struct Detection
{
  cv::Rect2f box;     ///< window [image px]
  float score = 0.f;  ///< linear SVM decision value w.x + b (> 0 = positive side) [unitless]
  float scale = 1.f;  ///< pyramid level scale the window was found at (level px per image px; 1 = full size)
  int cell_size = 0;  ///< pooling cell side at that level [level px]
  int level = 0;      ///< pyramid level index of the scan that found it
  cv::Point origin;   ///< window's top-left pixel on that level [level px] (for its dense features)
};
}  // namespace biovision_hri
