#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "biovision_v1/scale_responses.hpp"

namespace biovision_v1
{
/// Complex and end-stopped cells of one scale (Rodrigues & du Buf 2006), on the scale's grid.
///
/// With t_i the bar direction and n_i its normal of orientation i, and d = offset * lambda (grid px):
///   single end-stopped  S_i(p) = |C_i(p + d t_i) - C_i(p - d t_i)|           (both end polarities)
///   double end-stopped  D_i(p) = [C_i(p) - C_i(p + 2d t_i)/2 - C_i(p - 2d t_i)/2]^+
/// They respond where a line or edge ends, bends or meets another: first and second differences of
/// the complex cells along the orientation.
class EndStoppedCells
{
public:
  /// offset: d in wavelengths (Rodrigues & du Buf use 0.6). with_double = false skips the double
  /// end-stopped cells (the line/edge map needs only the single ones); doubleStopped() is then empty.
  EndStoppedCells(const ScaleResponses& responses, double offset = 0.6, bool with_double = true);

  const std::vector<cv::Mat>& complexCells() const { return complex_; }
  const std::vector<cv::Mat>& singleStopped() const { return single_; }
  const std::vector<cv::Mat>& doubleStopped() const { return double_; }
  /// d [grid px].
  double offset() const { return d_; }
  /// Largest complex-cell response over orientations and grid: the scale's contrast.
  double maxComplex() const { return max_complex_; }
  /// Bar direction t_i = (-sin theta_i, cos theta_i) and normal n_i = (cos theta_i, sin theta_i).
  cv::Point2f tangent(int i) const;
  cv::Point2f normal(int i) const;

  /// dst(p) = src(p + offset), bilinear, edges replicated.
  static cv::Mat shifted(const cv::Mat& src, const cv::Point2f& offset);

private:
  int orientations_;
  double d_;
  double max_complex_ = 0.0;
  std::vector<cv::Mat> complex_, single_, double_;
};
}  // namespace biovision_v1
