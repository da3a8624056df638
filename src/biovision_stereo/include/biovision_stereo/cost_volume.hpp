#pragma once

#include <cmath>
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
  /// The same over image rows [y0, y1) of every slice; std::out_of_range unless 0 <= y0 <= y1 <= height.
  float min(int y0, int y1) const;
  float max(int y0, int y1) const;
  /// Least / largest of the n values from `values` and `start` (a running extreme), NaN ignored: `start`
  /// when n <= 0 or every value is NaN, and a NaN `start` counts as +inf / -inf.
  static float lowestOf(const float* values, int n, float start = HUGE_VALF);
  static float highestOf(const float* values, int n, float start = -HUGE_VALF);
  /// This volume resampled to `size` x `disparities` (bilinear in x, y; linear in k): the
  /// coarse-to-fine upsampling of the thesis (m and k multiplied by sf).
  CostVolume resampled(cv::Size size, int disparities) const;

private:
  void requireRows(int y0, int y1) const;

  cv::Size size_;
  std::vector<cv::Mat> slices_;
};
}  // namespace biovision_stereo
