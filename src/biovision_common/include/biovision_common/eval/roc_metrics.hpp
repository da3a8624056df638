#pragma once

// Verification metrics of descriptor distances (descriptor_eval): matching pairs should be near,
// non-matching pairs far.

#include <algorithm>
#include <cmath>
#include <vector>

namespace biovision_common
{
/// Share of the distances <= t: the recall (matching pairs) or false-positive rate (non-matching pairs) of
/// a matcher that accepts every pair within radius t. 0 for no distances.
inline double shareWithin(const std::vector<float>& distances, float t)
{
  if (distances.empty())
    return 0.0;
  return static_cast<double>(std::count_if(distances.begin(), distances.end(), [t](float d) { return d <= t; })) /
         distances.size();
}

/// False-positive rate at the first distance threshold t whose recall P(d_pos <= t) reaches 95%.
inline double fpr95AtThreshold(std::vector<float> pos, const std::vector<float>& neg)
{
  if (pos.empty() || neg.empty())
    return 1.0;
  std::sort(pos.begin(), pos.end());
  return shareWithin(neg, pos[static_cast<size_t>(std::ceil(0.95 * pos.size())) - 1]);
}

/// False-positive rate at exactly 95% recall on the ROC curve: between the two thresholds whose recall
/// brackets 95%, pairs at the upper threshold's distance are accepted in random order (linear
/// interpolation), so integer Hamming distances with many ties are not charged for the whole tie.
inline double fpr95(std::vector<float> pos, std::vector<float> neg)
{
  if (pos.empty() || neg.empty())
    return 1.0;
  std::sort(pos.begin(), pos.end());
  std::sort(neg.begin(), neg.end());
  const double target = 0.95 * pos.size();
  const float t = pos[static_cast<size_t>(std::ceil(target)) - 1];
  const double pos_below = std::lower_bound(pos.begin(), pos.end(), t) - pos.begin();
  const double pos_at = std::upper_bound(pos.begin(), pos.end(), t) - pos.begin() - pos_below;
  const double neg_below = std::lower_bound(neg.begin(), neg.end(), t) - neg.begin();
  const double neg_at = std::upper_bound(neg.begin(), neg.end(), t) - neg.begin() - neg_below;
  const double fraction = (target - pos_below) / pos_at;  // of the tie at t accepted to reach 95%
  return (neg_below + fraction * neg_at) / neg.size();
}

inline double rocArea(const std::vector<float>& pos, std::vector<float> neg)
{
  // P(d_negative > d_positive), ties half.
  std::sort(neg.begin(), neg.end());
  double sum = 0.0;
  for (float p : pos)
  {
    const auto lo = std::lower_bound(neg.begin(), neg.end(), p), hi = std::upper_bound(neg.begin(), neg.end(), p);
    sum += (neg.end() - hi) + 0.5 * (hi - lo);
  }
  return pos.empty() || neg.empty() ? 0.0 : sum / (double(pos.size()) * neg.size());
}
}  // namespace biovision_common
