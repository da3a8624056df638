#include "biovision_sim/kinematic_chain.hpp"

#include <algorithm>

namespace biovision_sim
{
Eigen::Isometry3d KinematicChain::evaluate(const std::vector<std::string>& names,
                                           const std::vector<double>& positions) const
{
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (const Link& l : links_)
  {
    t = t * l.origin;
    if (l.joint.empty())
      continue;
    const auto it = std::find(names.begin(), names.end(), l.joint);
    if (it != names.end())
      t = t * Eigen::AngleAxisd(positions[it - names.begin()], l.axis.normalized());
  }
  return t;
}
}  // namespace biovision_sim
