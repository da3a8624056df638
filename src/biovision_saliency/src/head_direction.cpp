#include "biovision_saliency/head_direction.hpp"

#include <cmath>

namespace biovision_saliency
{
cv::Point2d HeadDirection::directionOf(const cv::Point2f& p) const
{
  return cv::Point2d(pan + std::atan((principal.x - p.x) / focal), tilt + std::atan((p.y - principal.y) / focal));
}
}  // namespace biovision_saliency
