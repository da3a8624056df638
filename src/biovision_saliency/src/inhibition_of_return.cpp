#include "biovision_saliency/inhibition_of_return.hpp"

#include <algorithm>
#include <cmath>

namespace biovision_saliency
{
InhibitionOfReturn::InhibitionOfReturn(double radius, double decay_time) : radius_(radius), decay_time_(decay_time)
{
}

void InhibitionOfReturn::attend(const cv::Point2d& direction, double t)
{
  memories_.erase(std::remove_if(memories_.begin(), memories_.end(),
                                 [&](const Memory& m) { return t - m.time >= decay_time_; }),
                  memories_.end());
  memories_.push_back({direction, t});
}

double InhibitionOfReturn::inhibition(const cv::Point2d& direction, double t) const
{
  double strongest = 0.0;
  for (const Memory& m : memories_)
  {
    const double age = t - m.time;
    if (age < 0 || age >= decay_time_)
      continue;
    if (std::hypot(direction.x - m.direction.x, direction.y - m.direction.y) <= radius_)
      strongest = std::max(strongest, 1.0 - age / decay_time_);
  }
  return strongest;
}

void InhibitionOfReturn::reset()
{
  memories_.clear();
}

size_t InhibitionOfReturn::size(double t) const
{
  return static_cast<size_t>(
      std::count_if(memories_.begin(), memories_.end(), [&](const Memory& m) { return t - m.time < decay_time_; }));
}
}  // namespace biovision_saliency
