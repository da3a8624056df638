#pragma once

#include <string>
#include <vector>

#include "biovision_attractor/base_attractor.hpp"

namespace biovision_attractor
{
/// Where navigation_eval takes the short-term memory from: one implementation per source, chosen by name
/// (--stm). The ground-truth range source is the first; a disparity-based biovision_memory source plugs in
/// here later. Poses are the simulator's world frame (x, y [m], yaw [rad]); the result is base_link sectors.
class StmSource
{
public:
  virtual ~StmSource() = default;
  /// The name recorded in the JSON and the docs.
  virtual std::string name() const = 0;
  /// One STM update with the base at (x, y, yaw) and the head at `pan` [rad, + = left], time t [s].
  virtual std::vector<BaseAttractor::Sector> update(double x, double y, double yaw, double pan, double t) = 0;
};
}  // namespace biovision_attractor
