#include "biovision_stereo/cost_volume.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace biovision_stereo
{
CostVolume::CostVolume(cv::Size size, int disparities, float value) : size_(size)
{
  slices_.reserve(disparities);
  for (int k = 0; k < disparities; ++k)
    slices_.emplace_back(size, CV_32F, cv::Scalar(value));
}

void CostVolume::create(cv::Size size, int disparities)
{
  size_ = size;
  slices_.resize(disparities);
  for (cv::Mat& s : slices_)
    s.create(size, CV_32F);
}

namespace
{
// Least (lowest) or largest of n values, NaN ignored, from the running extreme m. cv::minMaxLoc tracks the
// location as well and took 8% of BioBin's time (perf, Middlebury) for the two calls per frame.
template <bool kLowest>
float extremeOf(const float* p, int n, float m)
{
  int x = 0;
#if defined(__SSE2__)
  __m128 a = _mm_set1_ps(m), b = a;
  for (; x + 8 <= n; x += 8)
  {
    // (value, accumulator): a NaN value keeps the accumulator.
    a = kLowest ? _mm_min_ps(_mm_loadu_ps(p + x), a) : _mm_max_ps(_mm_loadu_ps(p + x), a);
    b = kLowest ? _mm_min_ps(_mm_loadu_ps(p + x + 4), b) : _mm_max_ps(_mm_loadu_ps(p + x + 4), b);
  }
  alignas(16) float lanes[8];
  _mm_store_ps(lanes, a);
  _mm_store_ps(lanes + 4, b);
  for (const float v : lanes)
    m = kLowest ? std::min(m, v) : std::max(m, v);
#endif
  for (; x < n; ++x)
    if (!std::isnan(p[x]))
      m = kLowest ? std::min(m, p[x]) : std::max(m, p[x]);
  return m;
}

// The same over image rows [y0, y1) of every slice.
template <bool kLowest>
float extreme(const std::vector<cv::Mat>& slices, int y0, int y1)
{
  float m = kLowest ? HUGE_VALF : -HUGE_VALF;
  for (const cv::Mat& s : slices)
    for (int y = y0; y < y1; ++y)
      m = extremeOf<kLowest>(s.ptr<float>(y), s.cols, m);
  return m;
}
}  // namespace

float CostVolume::lowestOf(const float* values, int n, float start)
{
  return extremeOf<true>(values, n, std::isnan(start) ? HUGE_VALF : start);
}

float CostVolume::highestOf(const float* values, int n, float start)
{
  return extremeOf<false>(values, n, std::isnan(start) ? -HUGE_VALF : start);
}

float CostVolume::min() const
{
  return extreme<true>(slices_, 0, size_.height);
}

float CostVolume::max() const
{
  return extreme<false>(slices_, 0, size_.height);
}

void CostVolume::requireRows(int y0, int y1) const
{
  if (y0 < 0 || y1 < y0 || y1 > size_.height)
    throw std::out_of_range("CostVolume: rows [" + std::to_string(y0) + ", " + std::to_string(y1) +
                            ") outside a volume of height " + std::to_string(size_.height));
}

float CostVolume::min(int y0, int y1) const
{
  requireRows(y0, y1);
  return extreme<true>(slices_, y0, y1);
}

float CostVolume::max(int y0, int y1) const
{
  requireRows(y0, y1);
  return extreme<false>(slices_, y0, y1);
}

CostVolume CostVolume::resampled(cv::Size size, int disparities) const
{
  CostVolume out;
  out.size_ = size;
  out.slices_.resize(disparities);
  const int d_in = this->disparities();
  const double scale = disparities > 1 ? double(d_in - 1) / double(disparities - 1) : 0.0;
  cv::Mat mixed;
  for (int k = 0; k < disparities; ++k)
  {
    const double kc = k * scale;
    const int k0 = std::min(static_cast<int>(kc), d_in - 1), k1 = std::min(k0 + 1, d_in - 1);
    const double t = kc - k0;
    cv::addWeighted(slices_[k0], 1.0 - t, slices_[k1], t, 0.0, mixed);
    cv::resize(mixed, out.slices_[k], size, 0, 0, cv::INTER_LINEAR);
  }
  return out;
}
}  // namespace biovision_stereo
