#include "biovision_hri/non_maximum_suppression.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace biovision_hri
{
double intersectionOverUnion(const cv::Rect2f& a, const cv::Rect2f& b)
{
  const double inter = (a & b).area();
  const double uni = static_cast<double>(a.area()) + b.area() - inter;
  return uni > 0.0 ? inter / uni : 0.0;
}

std::vector<Detection> nonMaximumSuppression(std::vector<Detection> detections, double overlap)
{
  if (!(overlap > 0.0 && overlap <= 1.0))
    throw std::invalid_argument("nonMaximumSuppression: overlap must be in (0, 1], got " + std::to_string(overlap));
  std::stable_sort(detections.begin(), detections.end(),
                   [](const Detection& a, const Detection& b) { return a.score > b.score; });
  std::vector<Detection> kept;
  for (const Detection& d : detections)
  {
    const bool suppressed = std::any_of(kept.begin(), kept.end(), [&](const Detection& k) {
      return intersectionOverUnion(k.box, d.box) >= overlap;
    });
    if (!suppressed)
      kept.push_back(d);
  }
  return kept;
}
}  // namespace biovision_hri
