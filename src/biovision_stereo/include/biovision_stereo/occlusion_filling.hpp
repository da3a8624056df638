#pragma once

#include <opencv2/core.hpp>

namespace biovision_stereo
{
/// Fills the pixels a left-right check invalidated, as Hirschmueller (2008, section 3.4) does for
/// occlusions: an occluded pixel belongs to the background, so it takes the smaller (farther) of the
/// nearest valid disparities to its left and right on the same row (the only one where the row has one
/// side valid; left untouched where the whole row is invalid). Beyond the thesis; issue #22.
class OcclusionFilling
{
public:
  /// disparity: CV_32FC1, invalid pixels < 0 (DisparityMap::kInvalid), filled in place.
  /// Throws std::invalid_argument for another type.
  static void fill(cv::Mat& disparity);
};
}  // namespace biovision_stereo
