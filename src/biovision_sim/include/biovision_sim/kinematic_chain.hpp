#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace biovision_sim
{
/// A serial chain of fixed transforms and revolute joints (from a URDF), evaluated for joint angles:
/// parent_from_child = prod(origin_i * rotation(axis_i, q_i)). Used to place the cameras exactly where
/// the robot description (and so tf) puts them.
class KinematicChain
{
public:
  struct Link
  {
    Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  ///< joint origin in the parent link
    std::string joint;                                         ///< "" for a fixed joint
    Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();           ///< revolute axis in the joint frame
  };

  void append(const Link& link) { links_.push_back(link); }
  /// Root-from-tip transform; joints not named in `names` stay at 0.
  Eigen::Isometry3d evaluate(const std::vector<std::string>& names, const std::vector<double>& positions) const;
  const std::vector<Link>& links() const { return links_; }

private:
  std::vector<Link> links_;
};
}  // namespace biovision_sim
