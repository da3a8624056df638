#pragma once

#include <opencv2/core.hpp>

namespace biovision_common
{
/// Middlebury-style error figures of a disparity map against ground truth, over the pixels where the
/// ground truth is known and the mask (if any) is set.
struct DisparityMetrics
{
  double bad05 = 0, bad1 = 0, bad2 = 0, bad4 = 0;  ///< % of pixels with error > 0.5/1/2/4 px; invalid = bad
  double avgerr = 0;                               ///< mean |error| [px] over pixels with a valid estimate
  double invalid = 0;  ///< % of pixels without an estimate (negative or non-finite disparity)
  long pixels = 0;     ///< pixels evaluated

  /// disparity: CV_32F, invalid < 0 or non-finite. ground_truth: CV_32F, unknown <= 0 or non-finite.
  /// mask: CV_8U (non-zero = evaluate) or empty.
  static DisparityMetrics compute(const cv::Mat& disparity, const cv::Mat& ground_truth,
                                  const cv::Mat& mask = cv::Mat());
};
}  // namespace biovision_common
