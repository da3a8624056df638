#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace biovision_saliency
{
/// Band-pass Difference-of-Gaussians blob detector (sigma- = 2 sigma+) at several scales.
/// conspicuity(map) = sum over scales of [DoG * map]^+; because the DoG is DC-free, the same filtering
/// of the map's complement (1 - map, or -map) is exactly [DoG * map]^-, so one filtering gives a map
/// and its complement: `positiveAndNegative`.
class BlobFilterBank
{
public:
  /// sigmas: centre sigmas sigma+ in working-resolution pixels. pyramid_sigma [working px]: a blur of
  /// sigma s runs on the coarsest pyrDown level where s / 2^level >= pyramid_sigma (the pyramid's own
  /// smoothing subtracted, upsampled bilinearly), as Itti-Koch-style models compute their centre-surround
  /// maps on a pyramid; 0 = every blur exactly at the working resolution.
  explicit BlobFilterBank(std::vector<double> sigmas, double pyramid_sigma = 0.0);

  /// Sum over scales of the rectified DoG responses: (on, off) = ([.]^+, [.]^-). map: CV_32F.
  void positiveAndNegative(const cv::Mat& map, cv::Mat& on, cv::Mat& off) const;
  /// Sum over scales of [DoG * map]^+.
  cv::Mat positive(const cv::Mat& map) const;

  const std::vector<double>& sigmas() const { return sigmas_; }

private:
  void filter(const cv::Mat& map, cv::Mat& on, cv::Mat* off) const;

  std::vector<double> sigmas_;
  double pyramid_sigma_;
};
}  // namespace biovision_saliency
