#include "biovision_common/eval/disparity_metrics.hpp"

#include <cmath>

namespace biovision_common
{
DisparityMetrics DisparityMetrics::compute(const cv::Mat& disparity, const cv::Mat& ground_truth, const cv::Mat& mask)
{
  CV_Assert(disparity.type() == CV_32FC1 && ground_truth.type() == CV_32FC1 && disparity.size() == ground_truth.size());
  CV_Assert(mask.empty() || (mask.type() == CV_8UC1 && mask.size() == disparity.size()));
  DisparityMetrics m;
  long b05 = 0, b1 = 0, b2 = 0, b4 = 0, invalid = 0, valid = 0;
  double err_sum = 0;
  for (int y = 0; y < disparity.rows; ++y)
  {
    const float* d = disparity.ptr<float>(y);
    const float* g = ground_truth.ptr<float>(y);
    const uchar* k = mask.empty() ? nullptr : mask.ptr<uchar>(y);
    for (int x = 0; x < disparity.cols; ++x)
    {
      if (!(std::isfinite(g[x]) && g[x] > 0) || (k && !k[x]))
        continue;
      ++m.pixels;
      if (!(std::isfinite(d[x]) && d[x] >= 0))
      {
        ++invalid;
        ++b05, ++b1, ++b2, ++b4;
        continue;
      }
      const double e = std::abs(d[x] - g[x]);
      ++valid;
      err_sum += e;
      b05 += e > 0.5;
      b1 += e > 1.0;
      b2 += e > 2.0;
      b4 += e > 4.0;
    }
  }
  if (m.pixels == 0)
    return m;
  const double pct = 100.0 / m.pixels;
  m.bad05 = b05 * pct;
  m.bad1 = b1 * pct;
  m.bad2 = b2 * pct;
  m.bad4 = b4 * pct;
  m.invalid = invalid * pct;
  m.avgerr = valid ? err_sum / valid : 0.0;
  return m;
}
}  // namespace biovision_common
