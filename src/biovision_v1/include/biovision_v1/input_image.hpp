#pragma once

#include <opencv2/core.hpp>

namespace biovision_v1
{
/// The one defined conversion from whatever a camera or a file gives to what the V1 model reads:
/// single-channel CV_32F, intensities in [0, 1].
///
/// - CV_8U is divided by 255, CV_16U by 65535; CV_32F/CV_64F are taken as they are (already [0, 1]).
/// - 3/4 channels are read as BGR(A) and turned into luminance (cv::COLOR_BGR2GRAY weights).
/// - NaN and +/-Inf pixels are replaced by 0 and counted in nonfinite_pixels.
/// - Empty input, unsupported depths (signed ints) or channel counts, and images smaller than
///   kMinSide on a side throw std::invalid_argument with a message saying which.
class InputImage
{
public:
  static constexpr int kMinSide = 8;

  explicit InputImage(const cv::Mat& image);

  const cv::Mat& gray() const { return gray_; }
  int nonfinitePixels() const { return nonfinite_pixels_; }

private:
  cv::Mat gray_;
  int nonfinite_pixels_ = 0;
};
}  // namespace biovision_v1
