#include "biovision_common/eval/saliency_metrics.hpp"

#include <cmath>

#include <opencv2/imgproc.hpp>

namespace biovision_common
{
namespace
{
cv::Mat asDistribution(const cv::Mat& m)
{
  cv::Mat shifted = m - cv::Scalar::all(0);
  double mn = 0;
  cv::minMaxLoc(m, &mn, nullptr);
  if (mn < 0)
    shifted = m - mn;
  const double sum = cv::sum(shifted)[0];
  return sum > 0 ? cv::Mat(shifted / sum) : cv::Mat(cv::Mat::zeros(m.size(), CV_32F));
}
}  // namespace

std::vector<cv::Point> SaliencyMetrics::peaks(const cv::Mat& fixations, int r, double fraction)
{
  double mx = 0;
  cv::minMaxLoc(fixations, nullptr, &mx);
  cv::Mat dilated;
  cv::dilate(fixations, dilated, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * r + 1, 2 * r + 1)));
  std::vector<cv::Point> points;
  for (int y = 0; y < fixations.rows; ++y)
    for (int x = 0; x < fixations.cols; ++x)
    {
      const float v = fixations.at<float>(y, x);
      if (v >= fraction * mx && v > 0 && v >= dilated.at<float>(y, x))
        points.emplace_back(x, y);
    }
  return points;
}

SaliencyMetrics SaliencyMetrics::compute(const cv::Mat& saliency, const cv::Mat& fixations)
{
  CV_Assert(saliency.type() == CV_32FC1 && fixations.type() == CV_32FC1 && saliency.size() == fixations.size());
  SaliencyMetrics m;
  cv::Scalar ms, ss, mf, sf;
  cv::meanStdDev(saliency, ms, ss);
  cv::meanStdDev(fixations, mf, sf);
  if (ss[0] > 0 && sf[0] > 0)
  {
    const cv::Mat zs = (saliency - ms[0]) / ss[0], zf = (fixations - mf[0]) / sf[0];
    m.cc = cv::mean(zs.mul(zf))[0];
    double nss = 0;
    const auto points = peaks(fixations);
    for (const auto& p : points)
      nss += zs.at<float>(p);
    m.nss = points.empty() ? 0 : nss / points.size();
  }
  const cv::Mat p = asDistribution(saliency), q = asDistribution(fixations);
  m.sim = cv::sum(cv::min(p, q))[0];
  constexpr double eps = 2.2204e-16;  // the benchmark's epsilon
  double kl = 0;
  for (int y = 0; y < q.rows; ++y)
    for (int x = 0; x < q.cols; ++x)
    {
      const double qv = q.at<float>(y, x), pv = p.at<float>(y, x);
      kl += qv * std::log(eps + qv / (pv + eps));
    }
  m.kl = kl;
  return m;
}
}  // namespace biovision_common
