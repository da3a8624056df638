#include "ground_truth_range_stm.hpp"

#include <cmath>
#include <limits>

#include "biovision_attractor/forcelets.hpp"

namespace biovision_attractor
{
namespace
{
constexpr int kSectors = BaseAttractorParameters::kSectors;
constexpr double kInf = std::numeric_limits<double>::infinity();

double wrap(double a)
{
  return std::atan2(std::sin(a), std::cos(a));
}
}  // namespace

GroundTruthRangeStm::GroundTruthRangeStm(const biovision_sim::FloorPlan& plan, const Options& options)
  : plan_(plan), options_(options), looked_(kSectors, -kInf)
{
}

std::vector<BaseAttractor::Sector> GroundTruthRangeStm::update(double x, double y, double yaw, double pan, double t)
{
  auto bearingOf = [&](const Point& p) { return wrap(std::atan2(p.y - y, p.x - x) - yaw); };
  // Forget what left the 180 deg field ("removed as soon as they are beyond the 180 deg range", thesis
  // L1247) or got too old.
  std::vector<Point> kept;
  for (const Point& p : points_)
    if (std::abs(bearingOf(p)) <= M_PI / 2 && t - p.seen <= 3 * options_.memory_time)
      kept.push_back(p);
  points_ = std::move(kept);

  // In view: each strip's nearest obstacle.
  const double strip = options_.horizontal_fov / options_.strips;
  for (int s = 0; s < options_.strips; ++s)
  {
    const double centre = pan - options_.horizontal_fov / 2 + strip * (s + 0.5);
    if (std::abs(centre) > M_PI / 2)
      continue;
    looked_[sectorOf(centre, kSectors, M_PI)] = t;
    double nearest = kInf, nearest_bearing = centre;
    const int rays = std::max(1, static_cast<int>(std::ceil(strip / options_.ray_step)));
    for (int r = 0; r <= rays; ++r)
    {
      const double bearing = centre - strip / 2 + strip * r / rays;
      const double d = plan_.range(x, y, yaw + bearing, options_.max_range);
      if (d < nearest)
      {
        nearest = d;
        nearest_bearing = bearing;
      }
    }
    // Remembered points in the strip's span nearer than what it sees now are gone.
    std::vector<Point> still;
    for (const Point& p : points_)
      if (!(std::abs(wrap(bearingOf(p) - centre)) <= strip / 2 && std::hypot(p.x - x, p.y - y) < nearest - 0.05))
        still.push_back(p);
    points_ = std::move(still);
    if (nearest < kInf)
      points_.push_back(
          {x + nearest * std::cos(yaw + nearest_bearing), y + nearest * std::sin(yaw + nearest_bearing), t});
  }
  if (static_cast<int>(points_.size()) > options_.max_points)
    points_.erase(points_.begin(), points_.begin() + (points_.size() - options_.max_points));

  std::vector<BaseAttractor::Sector> out(kSectors);
  for (int k = 0; k < kSectors; ++k)
  {
    out[k].angle = sectorCentre(k, kSectors, M_PI);
    out[k].distance = kInf;
    out[k].confidence = std::isfinite(looked_[k]) ? std::exp(-(t - looked_[k]) / options_.memory_time) : 0.0;
  }
  for (const Point& p : points_)
  {
    const int k = sectorOf(bearingOf(p), kSectors, M_PI);
    const double d = std::hypot(p.x - x, p.y - y);
    if (d < out[k].distance)
    {
      out[k].distance = d;
      out[k].confidence = std::exp(-(t - p.seen) / options_.memory_time);
    }
  }
  return out;
}
}  // namespace biovision_attractor
