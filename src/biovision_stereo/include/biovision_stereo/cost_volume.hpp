#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace biovision_stereo
{
/// Matching costs M(x, y, k) for disparities k = 0..disparities-1, stored as one CV_32F H x W slice
/// per disparity, so that per-disparity image operations (spatial filtering, resizing) are plain
/// OpenCV calls and operations along k run over contiguous rows.
class CostVolume
{
public:
  CostVolume() = default;
  CostVolume(cv::Size size, int disparities, float value = 0.f);

  /// Reshape to size x disparities, keeping the memory when the shape is unchanged (values are then
  /// left as they were, otherwise undefined): for buffers reused frame after frame.
  void create(cv::Size size, int disparities);

  cv::Size size() const { return size_; }
  int disparities() const { return static_cast<int>(slices_.size()); }
  cv::Mat& slice(int k) { return slices_[k]; }
  const cv::Mat& slice(int k) const { return slices_[k]; }
  float at(int x, int y, int k) const { return slices_[k].at<float>(y, x); }

  /// Least value over the whole volume, NaN ignored (+inf when empty or all NaN).
  float min() const;
  /// Largest value over the whole volume, NaN ignored (-inf when empty or all NaN).
  float max() const;
  /// This volume resampled to `size` x `disparities` (bilinear in x, y; linear in k): the
  /// coarse-to-fine upsampling of the thesis (m and k multiplied by sf).
  CostVolume resampled(cv::Size size, int disparities) const;

private:
  cv::Size size_;
  std::vector<cv::Mat> slices_;
};
}  // namespace biovision_stereo
