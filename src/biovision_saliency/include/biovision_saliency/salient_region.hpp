#pragma once

#include <opencv2/core.hpp>

namespace biovision_saliency
{
/// One salient region, in full-resolution image coordinates.
struct SalientRegion
{
  cv::Rect box;            ///< bounding box grown by the margin, clipped to the image [px]
  float peak = 0.f;        ///< maximum of the fused map inside the region [0, 1]
  float mean = 0.f;        ///< mean of the fused map inside the region [0, 1]
  int area = 0;            ///< region area before growing [full-resolution px^2]
  cv::Point2f centre;      ///< peak location [px]
  float pan = 0.f;         ///< head-centred direction of the peak [rad, + = left]
  float tilt = 0.f;        ///< [rad, + = down]
  float inhibition = 0.f;  ///< IoR level when ranked [0, 1]
  float priority = 0.f;    ///< peak * (1 - inhibition): the FoA order key
};
}  // namespace biovision_saliency
