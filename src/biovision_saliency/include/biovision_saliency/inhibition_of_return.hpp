#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace biovision_saliency
{
/// Inhibition-of-Return in head-centred angles: an attended direction inhibits regions whose
/// direction is within `radius`; the inhibition starts at 1 and falls linearly to 0 over
/// `decay_time`, after which the direction is released and forgotten.
class InhibitionOfReturn
{
public:
  InhibitionOfReturn(double radius, double decay_time);

  /// Marks a direction (pan, tilt) [rad] as attended at time t [s].
  void attend(const cv::Point2d& direction, double t);
  /// Inhibition of a direction at time t: the strongest of the memories covering it, [0, 1].
  double inhibition(const cv::Point2d& direction, double t) const;
  /// Forgets every memory.
  void reset();
  /// Memories still active at time t (older ones are dropped by attend/inhibition calls).
  size_t size(double t) const;

private:
  struct Memory
  {
    cv::Point2d direction;
    double time;
  };
  double radius_, decay_time_;
  std::vector<Memory> memories_;
};
}  // namespace biovision_saliency
