#pragma once

#include <opencv2/core.hpp>

namespace biovision_stereo
{
/// A left-view disparity map at input resolution: CV_32F, disparity in input pixels, and
/// kInvalid where no disparity is known (occluded, failed left-right check, no match possible).
struct DisparityMap
{
  static constexpr float kInvalid = -1.f;
  cv::Mat disparity;
  int max_disparity = 0;  ///< largest disparity searched [input px]

  cv::Mat validMask() const { return disparity >= 0.f; }
};
}  // namespace biovision_stereo
