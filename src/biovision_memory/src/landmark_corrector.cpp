#include "biovision_memory/landmark_corrector.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace biovision_memory
{
void LandmarkCorrectorParameters::validate() const
{
  auto check = [](const char* field, double v, double lo, double hi, bool lo_open) {
    if (!std::isfinite(v) || (lo_open ? v <= lo : v < lo) || v > hi)
    {
      std::ostringstream m;
      m << "LandmarkCorrectorParameters." << field << " = " << v << " is outside " << (lo_open ? "(" : "[") << lo
        << ", " << hi << "]";
      throw std::invalid_argument(m.str());
    }
  };
  check("window", window, 1, 10000, false);
  check("window_time", window_time, 0, 1e6, true);
  check("gain", gain, 0, 1, true);
  check("min_spread", min_spread, 0, 100, true);
  check("max_jump", max_jump, 0, 100, true);
  check("max_depth", max_depth, 0, 100, true);
}

LandmarkCorrector::LandmarkCorrector(const LandmarkCorrectorParameters& parameters) : parameters_(parameters)
{
  parameters_.validate();
}

void LandmarkCorrector::setParameters(const LandmarkCorrectorParameters& parameters)
{
  parameters.validate();
  parameters_ = parameters;
}

void LandmarkCorrector::reset(const Pose2D& map_from_odom)
{
  window_.clear();
  map_from_odom_ = map_from_odom;
}

bool LandmarkCorrector::observe(const Eigen::Vector2d& map_position, const Eigen::Vector2d& odom_position, double stamp,
                                double depth)
{
  if (!map_position.allFinite() || !odom_position.allFinite() || !std::isfinite(stamp) || !(depth >= 0.0) ||
      depth > parameters_.max_depth)
    return false;
  // Outlier: this sighting alone disagrees with the current estimate by more than max_jump.
  if ((map_from_odom_.apply(odom_position) - map_position).norm() > parameters_.max_jump)
    return false;
  window_.push_back({map_position, odom_position, stamp});
  while (static_cast<int>(window_.size()) > parameters_.window ||
         (!window_.empty() && stamp - window_.front().stamp > parameters_.window_time))
    window_.pop_front();
  if (!window_.empty() && window_.front().stamp > stamp)  // time went back: start over
  {
    window_.clear();
    window_.push_back({map_position, odom_position, stamp});
  }

  Eigen::Vector2d mo = Eigen::Vector2d::Zero(), mm = Eigen::Vector2d::Zero();
  for (const Pair& p : window_)
  {
    mo += p.odom;
    mm += p.map;
  }
  mo /= window_.size();
  mm /= window_.size();
  // The heading is observable only from landmarks apart in the map: one landmark seen from many places has
  // its odometry positions spread by noise and drift alone, and atan2 of that near-zero covariance is a
  // random angle (make demo, 2026-12-04: the target as sole landmark turned the map 30 deg about it, home
  // 9 m off). So the spread is the lesser of the two sides'.
  double spread_odom = 0.0, spread_map = 0.0, sxx = 0.0, sxy = 0.0;  // cross-covariance: Σ o·m and Σ o×m
  for (const Pair& p : window_)
  {
    const Eigen::Vector2d a = p.odom - mo, b = p.map - mm;
    spread_odom = std::max(spread_odom, a.norm());
    spread_map = std::max(spread_map, b.norm());
    sxx += a.dot(b);
    sxy += a.x() * b.y() - a.y() * b.x();
  }
  Pose2D fit;
  const double spread = std::min(spread_odom, spread_map);
  fit.yaw = spread >= parameters_.min_spread ? std::atan2(sxy, sxx) : map_from_odom_.yaw;
  const double c = std::cos(fit.yaw), s = std::sin(fit.yaw);
  fit.x = mm.x() - (c * mo.x() - s * mo.y());
  fit.y = mm.y() - (s * mo.x() + c * mo.y());

  const double g = parameters_.gain;
  map_from_odom_.x += g * (fit.x - map_from_odom_.x);
  map_from_odom_.y += g * (fit.y - map_from_odom_.y);
  map_from_odom_.yaw = Pose2D::normalizeAngle(map_from_odom_.yaw +
                                              g * Pose2D::normalizeAngle(fit.yaw - map_from_odom_.yaw));
  return true;
}
}  // namespace biovision_memory
