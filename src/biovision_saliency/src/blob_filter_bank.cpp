#include "biovision_saliency/blob_filter_bank.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <opencv2/imgproc.hpp>

namespace biovision_saliency
{
namespace
{
// Variance [px^2 of the finer level] that one pyrDown adds: its kernel (1 4 6 4 1)/16 has variance 1.
constexpr double kPyrDownVariance = 1.0;

// Gaussian blur of sigma `s` [px of `map`] at the coarsest pyramid level where s stays >= min_sigma_per_level
// working pixels, upsampled back bilinearly. `pyramid[l]` is `map` pyrDown'ed l times (filled on demand).
cv::Mat pyramidBlur(std::vector<cv::Mat>& pyramid, double s, double min_sigma_per_level)
{
  int level = 0;
  double variance_so_far = 0;  // the pyramid's own smoothing, in px^2 of the working resolution
  while (min_sigma_per_level > 0 && s / double(1 << (level + 1)) >= min_sigma_per_level && pyramid[level].cols >= 16 &&
         pyramid[level].rows >= 16)
  {
    variance_so_far += kPyrDownVariance * double(1 << level) * double(1 << level);
    ++level;
    if (static_cast<int>(pyramid.size()) <= level)
    {
      pyramid.emplace_back();
      cv::pyrDown(pyramid[level - 1], pyramid[level], cv::Size(), cv::BORDER_REPLICATE);
    }
  }
  cv::Mat out;
  const double rest = std::sqrt(std::max(0.0, s * s - variance_so_far)) / double(1 << level);
  if (rest > 0)
    cv::GaussianBlur(pyramid[level], out, cv::Size(), rest, rest, cv::BORDER_REPLICATE);
  else
    out = pyramid[level].clone();
  if (level > 0)
    cv::resize(out, out, pyramid[0].size(), 0, 0, cv::INTER_LINEAR);
  return out;
}
}  // namespace

BlobFilterBank::BlobFilterBank(std::vector<double> sigmas, double pyramid_sigma)
  : sigmas_(std::move(sigmas)), pyramid_sigma_(pyramid_sigma)
{
}

void BlobFilterBank::filter(const cv::Mat& map, cv::Mat& on, cv::Mat* off) const
{
  CV_Assert(map.type() == CV_32FC1);
  on = cv::Mat::zeros(map.size(), CV_32F);
  if (off)
    *off = cv::Mat::zeros(map.size(), CV_32F);
  // One blur per distinct sigma: with sigma- = 2 sigma+ and octave-spaced scales (5, 10, 20) the
  // surround of one scale is the centre of the next, so 4 blurs instead of 6.
  std::map<double, cv::Mat> blurred;
  std::vector<cv::Mat> pyramid{map};
  const auto blur = [&](double s) -> const cv::Mat& {
    auto it = blurred.find(s);
    if (it == blurred.end())
      it = blurred.emplace(s, pyramidBlur(pyramid, s, pyramid_sigma_)).first;
    return it->second;
  };
  // Rectified DoG accumulated in one pass per scale (no full-map temporaries: at 160x120 their
  // allocation and page faults cost more than the arithmetic, perf).
  for (double s : sigmas_)
  {
    const cv::Mat& centre = blur(s);
    const cv::Mat& surround = blur(2 * s);
    for (int y = 0; y < map.rows; ++y)
    {
      const float* c = centre.ptr<float>(y);
      const float* r = surround.ptr<float>(y);
      float* on_row = on.ptr<float>(y);
      float* off_row = off ? off->ptr<float>(y) : nullptr;
      for (int x = 0; x < map.cols; ++x)
        on_row[x] += std::max(c[x] - r[x], 0.f);
      if (off_row)
        for (int x = 0; x < map.cols; ++x)
          off_row[x] += std::max(r[x] - c[x], 0.f);
    }
  }
}

void BlobFilterBank::positiveAndNegative(const cv::Mat& map, cv::Mat& on, cv::Mat& off) const
{
  filter(map, on, &off);
}

cv::Mat BlobFilterBank::positive(const cv::Mat& map) const
{
  cv::Mat on;
  filter(map, on, nullptr);
  return on;
}
}  // namespace biovision_saliency
