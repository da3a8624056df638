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
  const cv::Matx23f m(1.f, 0.f, offset.x, 0.f, 1.f, offset.y);
  cv::Mat dst;
  cv::warpAffine(src, dst, m, src.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_REPLICATE);
  return dst;
}
}  // namespace biovision_v1
