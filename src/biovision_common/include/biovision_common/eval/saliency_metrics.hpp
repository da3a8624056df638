#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace biovision_common
{
/// Agreement of a saliency map with a continuous human fixation map (MIT saliency benchmark
/// definitions, Bylinskii et al. 2019). Both CV_32F of one size; the saliency map is resized by the
/// caller.
struct SaliencyMetrics
{
  double cc = 0;   ///< Pearson correlation of the two maps
  double sim = 0;  ///< histogram intersection of the maps normalised to unit sum, [0, 1]
  double kl = 0;   ///< KL(fixations || saliency) of the normalised maps (lower is better)
  double nss = 0;  ///< mean z-scored saliency at the fixation map's peaks

  static SaliencyMetrics compute(const cv::Mat& saliency, const cv::Mat& fixations);
  /// Fixation points standing in for the (unavailable) raw fixations: local maxima of the fixation
  /// map over a (2r+1)^2 window that reach `fraction` of its maximum.
  static std::vector<cv::Point> peaks(const cv::Mat& fixations, int r = 7, double fraction = 0.25);
};
}  // namespace biovision_common
