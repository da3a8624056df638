#include "biovision_stereo/cost_volume.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

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

float CostVolume::max() const
{
  double m = -HUGE_VAL;
  for (const cv::Mat& s : slices_)
  {
    double v;
    cv::minMaxLoc(s, nullptr, &v);
    m = std::max(m, v);
  }
  return static_cast<float>(m);
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
