#include "biovision_v1/direct_gabor_bank.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "biovision_v1/gabor_kernel.hpp"
#include "biovision_common/parallel_arena.hpp"

namespace biovision_v1
{
DirectGaborBank::DirectGaborBank(const GaborParameters& parameters) : parameters_(parameters)
{
  parameters_.validate();
}

std::vector<ScaleResponses> DirectGaborBank::compute(const cv::Mat& gray) const
{
  CV_Assert(gray.type() == CV_32FC1 && !gray.empty());
  const int n_scales = static_cast<int>(parameters_.wavelengths.size());
  const int n_orient = parameters_.orientations;
  std::vector<ScaleResponses> out(n_scales);
  for (int s = 0; s < n_scales; ++s)
  {
    out[s].wavelength = parameters_.wavelengths[s];
    out[s].decimation = 1;
    out[s].even.resize(n_orient);
    out[s].odd.resize(n_orient);
  }
  // One job per kernel (even and odd separately), as a filter bank user would run it.
  biovision_common::parallelFor(cv::Range(0, 2 * n_scales * n_orient), [&](const cv::Range& range) {
    for (int job = range.start; job < range.end; ++job)
    {
      const int s = job / (2 * n_orient), i = (job / 2) % n_orient;
      const bool odd = job % 2;
      const GaborKernel kernel(parameters_.wavelengths[s], parameters_.theta(i), parameters_);
      cv::filter2D(gray, odd ? out[s].odd[i] : out[s].even[i], CV_32F, odd ? kernel.odd() : kernel.even(),
                   cv::Point(-1, -1), 0.0, cv::BORDER_REFLECT_101);
    }
  });
  return out;
}

ScaleResponses DirectGaborBank::sampleLike(const ScaleResponses& full, const ScaleResponses& grid)
{
  ScaleResponses sampled;
  sampled.wavelength = full.wavelength;
  sampled.decimation = grid.decimation;
  const int d = grid.decimation;
  const cv::Size size = grid.gridSize();
  auto pick = [&](const cv::Mat& m) {
    cv::Mat s(size, CV_32F);
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x)
        s.at<float>(y, x) = m.at<float>(y * d, x * d);
    return s;
  };
  for (size_t i = 0; i < full.even.size(); ++i)
  {
    sampled.even.push_back(pick(full.even[i]));
    sampled.odd.push_back(pick(full.odd[i]));
  }
  return sampled;
}

double DirectGaborBank::maxRelativeError(const std::vector<ScaleResponses>& ours,
                                         const std::vector<ScaleResponses>& reference_full)
{
  CV_Assert(ours.size() == reference_full.size());
  double worst = 0.0;
  for (size_t s = 0; s < ours.size(); ++s)
  {
    const ScaleResponses ref = sampleLike(reference_full[s], ours[s]);
    for (size_t i = 0; i < ref.even.size(); ++i)
      for (int part = 0; part < 2; ++part)
      {
        const cv::Mat& a = part ? ours[s].odd[i] : ours[s].even[i];
        const cv::Mat& b = part ? ref.odd[i] : ref.even[i];
        const double scale = cv::norm(b, cv::NORM_INF);
        const double err = cv::norm(a, b, cv::NORM_INF);
        if (scale > 0)
          worst = std::max(worst, err / scale);
        else if (err > 0)
          worst = std::max(worst, err);
      }
  }
  return worst;
}
}  // namespace biovision_v1
