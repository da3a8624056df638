#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace biovision_stereo
{
/// Bilinear resampling of a CV_32FC1 image, row by row, equal bit for bit to cv::resize(src, dst, output,
/// 0, 0, cv::INTER_LINEAR) (OpenCV 4's coefficients: sample centres (d + 0.5) * in / out - 0.5 rounded to
/// float, the right border clamped, rows clipped; each row interpolated along x first, then the two rows
/// combined) — except where cv::resize does not interpolate: an output of exactly half the input on both
/// axes (OpenCV averages areas there; this class still interpolates) and an unchanged size (both copy, but
/// OpenCV's copy keeps an inf beside a pixel out of it, which a zero weight would not). What it adds: each output row goes to a callback while it is in the cache, so BioBin's fusion
/// averages a coarser level's slice into a finer one without storing the upsampled slice (a write and a
/// read of 675 KB per slice at Middlebury size).
class LinearResampling
{
public:
  /// Throws std::invalid_argument on an empty size.
  LinearResampling(cv::Size input, cv::Size output);

  cv::Size input() const { return input_; }
  cv::Size output() const { return output_; }

  /// Calls per_row(y, row) for y = 0 .. output().height - 1 with row = output row y (output().width
  /// floats, valid during the call). src: CV_32FC1 of input() size (not checked: the callers' own volumes);
  /// scratch: reused between calls.
  template <class PerRow>
  void forEachRow(const cv::Mat& src, std::vector<float>& scratch, PerRow&& per_row) const
  {
    const int w = output_.width;
    if (input_ == output_)  // a copy, as cv::resize makes it (no zero weight times a neighbouring inf)
    {
      for (int y = 0; y < output_.height; ++y)
        per_row(y, src.ptr<float>(y));
      return;
    }
    scratch.resize(3 * size_t(w));
    float* slot[2] = {scratch.data(), scratch.data() + w};
    float* out = scratch.data() + 2 * size_t(w);
    int held[2] = {-1, -1};  // the source row each slot holds, interpolated along x
    for (int y = 0; y < output_.height; ++y)
    {
      const int rows[2] = {row0_[y], row1_[y]};
      const float* along_x[2];
      for (int k = 0; k < 2; ++k)
      {
        int s = held[0] == rows[k] ? 0 : held[1] == rows[k] ? 1 : -1;
        if (s < 0)
        {
          s = held[0] == rows[1 - k] ? 1 : 0;  // keep the slot the other row needs
          alongX(src.ptr<float>(rows[k]), slot[s]);
          held[s] = rows[k];
        }
        along_x[k] = slot[s];
      }
      const float b0 = beta_[2 * y], b1 = beta_[2 * y + 1];
      const float* __restrict d0 = along_x[0];
      const float* __restrict d1 = along_x[1];
      for (int x = 0; x < w; ++x)
        out[x] = d0[x] * b0 + d1[x] * b1;
      per_row(y, static_cast<const float*>(out));
    }
  }

private:
  void alongX(const float* s, float* d) const
  {
    int x = 0;
    for (; x < x_max_; ++x)
      d[x] = s[x_offset_[x]] * alpha_[2 * x] + s[x_offset_[x] + 1] * alpha_[2 * x + 1];
    for (; x < output_.width; ++x)
      d[x] = s[x_offset_[x]] * 1.f;  // beyond the last sample: the border value itself
  }

  cv::Size input_, output_;
  std::vector<int> x_offset_, row0_, row1_;
  std::vector<float> alpha_, beta_;  // two per output column / row
  int x_max_ = 0;                    // columns from here on read one sample
};
}  // namespace biovision_stereo
