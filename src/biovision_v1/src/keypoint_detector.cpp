#include "biovision_v1/keypoint_detector.hpp"

#include <algorithm>
#include <cmath>

namespace biovision_v1
{
cv::Mat KeypointDetector::keypointMap(const EndStoppedCells& cells) const
{
  const auto& complex = cells.complexCells();
  const int n = static_cast<int>(complex.size());
  const cv::Size size = complex.front().size();
  cv::Mat excitation = cv::Mat::zeros(size, CV_32F), inhibition = cv::Mat::zeros(size, CV_32F);
  const float d = static_cast<float>(cells.offset());
  // For each orientation, the strongest response of the orientations at least 45 deg away from it.
  std::vector<cv::Mat> crossing(n);
  for (int i = 0; i < n; ++i)
  {
    crossing[i] = cv::Mat::zeros(size, CV_32F);
    for (int j = 0; j < n; ++j)
    {
      const int distance = std::min((i - j + n) % n, (j - i + n) % n);
      if (4 * distance >= n)
        crossing[i] = cv::max(crossing[i], complex[j]);
    }
  }
  for (int i = 0; i < n; ++i)
  {
    excitation += cells.singleStopped()[i];
    excitation += cells.doubleStopped()[i];
    const cv::Point2f nd = cells.normal(i) * d;
    for (float sense : {1.f, -1.f})
    {
      // Tangential: a stronger response across the bar means p lies beside a line or edge.
      inhibition += cv::max(EndStoppedCells::shifted(complex[i], sense * nd) - complex[i], 0.0);
      // Radial: along a straight line every clearly different orientation stays silent.
      const cv::Mat other = EndStoppedCells::shifted(crossing[i], sense * 0.5f * nd);
      inhibition += cv::max(complex[i] - parameters_.radial_factor * other, 0.0);
    }
  }
  cv::Mat k = excitation - parameters_.inhibition_gain * inhibition;
  k = cv::max(k, 0.0);
  if (parameters_.junction_weight > 0)
  {
    // Junction cells: an AND (minimum) of an orientation and a clearly different one. They peak
    // where the centre lines of crossing lines meet, where end-stopped cells see a ring instead.
    cv::Mat junction = cv::Mat::zeros(size, CV_32F);
    for (int i = 0; i < n; ++i)
    {
      // Balanced AND: a line leaks into the channels 45 deg away, but never as strongly as itself.
      const cv::Mat balanced = cv::min(complex[i], crossing[i]) -
                               parameters_.junction_balance * cv::max(complex[i], crossing[i]);
      junction += cv::max(balanced, 0.0);
    }
    k += parameters_.junction_weight * junction;
  }
  const double contrast = cells.maxComplex();
  if (contrast > 0)
    k /= contrast;
  return k;
}

std::vector<Keypoint> KeypointDetector::detect(const ScaleResponses& responses, const EndStoppedCells& cells) const
{
  std::vector<Keypoint> keypoints;
  if (cells.maxComplex() < parameters_.min_contrast)
    return keypoints;
  const cv::Mat k = keypointMap(cells);
  const int n = responses.orientations();
  const float threshold = static_cast<float>(parameters_.threshold);
  for (int y = 1; y + 1 < k.rows; ++y)
    for (int x = 1; x + 1 < k.cols; ++x)
    {
      const float v = k.at<float>(y, x);
      if (v < threshold)
        continue;
      bool is_max = true;
      for (int dy = -1; dy <= 1 && is_max; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
        {
          if (!dx && !dy)
            continue;
          const float w = k.at<float>(y + dy, x + dx);
          // Ties go to the first sample in raster order, so a plateau gives one keypoint.
          if (w > v || (w == v && (dy < 0 || (dy == 0 && dx < 0))))
          {
            is_max = false;
            break;
          }
        }
      if (!is_max)
        continue;
      // Sub-sample peak of a parabola through the neighbours, per axis.
      auto refine = [](float minus, float centre, float plus) {
        const float den = minus - 2 * centre + plus;
        return den < 0 ? std::clamp(0.5f * (minus - plus) / den, -0.5f, 0.5f) : 0.f;
      };
      const float ox = refine(k.at<float>(y, x - 1), v, k.at<float>(y, x + 1));
      const float oy = refine(k.at<float>(y - 1, x), v, k.at<float>(y + 1, x));
      // Dominant orientation: the strongest end-stopped cell here.
      int best_i = 0;
      float best = -1.f;
      for (int i = 0; i < n; ++i)
      {
        const float e = cells.singleStopped()[i].at<float>(y, x) + cells.doubleStopped()[i].at<float>(y, x);
        if (e > best)
        {
          best = e;
          best_i = i;
        }
      }
      const cv::Point2f p = responses.toImage(cv::Point2f(x + ox, y + oy));
      keypoints.push_back(
          {p.x, p.y, static_cast<float>(responses.wavelength), v, static_cast<float>(best_i * M_PI / n)});
    }
  return keypoints;
}
}  // namespace biovision_v1
