#include "biovision_v1/end_stopped_cells.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace biovision_v1
{
EndStoppedCells::EndStoppedCells(const ScaleResponses& responses, double offset, bool with_double)
  : orientations_(responses.orientations()), d_(offset * responses.gridWavelength())
{
  complex_ = responses.complexCells();
  single_.resize(orientations_);
  if (with_double)
    double_.resize(orientations_);
  for (int i = 0; i < orientations_; ++i)
  {
    double peak = 0.0;
    cv::minMaxLoc(complex_[i], nullptr, &peak);
    max_complex_ = std::max(max_complex_, peak);
    const cv::Point2f t = tangent(i) * static_cast<float>(d_);
    const cv::Mat ahead = shifted(complex_[i], t), behind = shifted(complex_[i], -t);
    single_[i] = cv::abs(ahead - behind);
    if (!with_double)
      continue;
    const cv::Mat ahead2 = shifted(complex_[i], 2 * t), behind2 = shifted(complex_[i], -2 * t);
    cv::Mat dbl = complex_[i] - 0.5 * ahead2 - 0.5 * behind2;
    double_[i] = cv::max(dbl, 0.0);
  }
}

cv::Point2f EndStoppedCells::tangent(int i) const
{
  const double theta = i * M_PI / orientations_;
  return cv::Point2f(static_cast<float>(-std::sin(theta)), static_cast<float>(std::cos(theta)));
}

cv::Point2f EndStoppedCells::normal(int i) const
{
  const double theta = i * M_PI / orientations_;
  return cv::Point2f(static_cast<float>(std::cos(theta)), static_cast<float>(std::sin(theta)));
}

cv::Mat EndStoppedCells::shifted(const cv::Mat& src, const cv::Point2f& offset)
{
  CV_Assert(src.type() == CV_32FC1);
  // One offset for the whole map, so the bilinear weights are constants: a padded copy and a weighted sum
  // of four shifted rows (exact weights, where cv::warpAffine quantises them to 1/32 and ran 5-10x slower:
  // it was a tenth of the perception loop's CPU under perf).
  const int ix = static_cast<int>(std::floor(offset.x)), iy = static_cast<int>(std::floor(offset.y));
  const float fx = offset.x - ix, fy = offset.y - iy;
  const int w = src.cols, h = src.rows;
  // Replicated margins wide enough for x + ix .. x + ix + 1 and y + iy .. y + iy + 1 (capped: beyond the
  // map every sample is an edge value anyway).
  const int left = std::clamp(-ix, 0, w + 1), right = std::clamp(ix + 1, 0, w + 1);
  const int top = std::clamp(-iy, 0, h + 1), bottom = std::clamp(iy + 1, 0, h + 1);
  cv::Mat padded;
  cv::copyMakeBorder(src, padded, top, bottom, left, right, cv::BORDER_REPLICATE);
  const float w00 = (1 - fx) * (1 - fy), w01 = fx * (1 - fy), w10 = (1 - fx) * fy, w11 = fx * fy;
  cv::Mat dst(src.size(), CV_32FC1);
  for (int y = 0; y < h; ++y)
  {
    // Source row y + iy (clamped into the padded map: far shifts read the replicated edge).
    const int r0 = std::clamp(y + iy + top, 0, padded.rows - 1), r1 = std::clamp(y + iy + 1 + top, 0, padded.rows - 1);
    const float* a = padded.ptr<float>(r0);
    const float* b = padded.ptr<float>(r1);
    float* out = dst.ptr<float>(y);
    const int c0 = ix + left;
    if (c0 >= 0 && c0 + w < padded.cols)
    {
      const float *a0 = a + c0, *b0 = b + c0;
      for (int x = 0; x < w; ++x)
        out[x] = w00 * a0[x] + w01 * a0[x + 1] + w10 * b0[x] + w11 * b0[x + 1];
    }
    else
      for (int x = 0; x < w; ++x)
      {
        const int x0 = std::clamp(x + c0, 0, padded.cols - 1), x1 = std::clamp(x + c0 + 1, 0, padded.cols - 1);
        out[x] = w00 * a[x0] + w01 * a[x1] + w10 * b[x0] + w11 * b[x1];
      }
  }
  return dst;
}
}  // namespace biovision_v1
