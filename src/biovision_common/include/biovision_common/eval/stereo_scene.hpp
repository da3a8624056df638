#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace biovision_common
{
/// A rectified stereo pair with ground truth, as loaded by MiddleburyDataset.
struct StereoScene
{
  std::string name;
  std::string layout;     ///< "v3", "v2-masks", "2005-2006", "2003", "2001", "tsukuba"
  cv::Mat left, right;    ///< 8-bit BGR
  cv::Mat ground_truth;   ///< CV_32F left disparity [px]; <= 0 or non-finite = unknown
  cv::Mat nonoccluded;    ///< CV_8U, 255 = evaluate here (non-occluded, known); empty = all known
  int max_disparity = 0;  ///< search range for every method [px]
};
}  // namespace biovision_common
