#include "biovision_tasks/mission_record.hpp"

#include <cmath>

namespace biovision_tasks
{
namespace
{
double distance(const cv::Point2d& a, const cv::Point2d& b)
{
  return std::hypot(a.x - b.x, a.y - b.y);
}
}  // namespace

void MissionRecord::extendTrail(double x, double y)
{
  if (!std::isfinite(x) || !std::isfinite(y))
    return;
  if (!trail.empty() && distance({x, y}, trail.back()) < kTrailSpacing)
    return;
  if (trail.size() >= kMaxTrail)
  {
    std::vector<cv::Point2d> thinned;
    for (size_t i = 0; i < trail.size(); i += 2)
      thinned.push_back(trail[i]);
    trail.swap(thinned);
  }
  trail.emplace_back(x, y);
}

std::vector<cv::Point2d> MissionRecord::wayBack(const cv::Point2d& from) const
{
  std::vector<cv::Point2d> route;
  if (trail.empty())
    return route;
  size_t k = 0;
  for (size_t i = 1; i < trail.size(); ++i)
    if (distance(trail[i], from) < distance(trail[k], from))
      k = i;
  route.push_back(trail[k]);
  while (k > 0)
  {
    // The oldest point near this one (a loop closes here), else the one before.
    size_t next = k - 1;
    for (size_t j = 0; j + 1 < k; ++j)
      if (distance(trail[j], trail[k]) < kLoopCut)
      {
        next = j;
        break;
      }
    k = next;
    route.push_back(trail[k]);
  }
  return route;
}
}  // namespace biovision_tasks
