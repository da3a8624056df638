#include "biovision_sim/floor_plan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace biovision_sim
{
namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();

// Entry distance t >= 0 of the ray p + t d into the footprint, +Inf when it misses.
double rayEntry(const FloorPlan::Footprint& f, double px, double py, double dx, double dy)
{
  const double ox = px - f.x, oy = py - f.y;
  if (f.disc)
  {
    const double b = ox * dx + oy * dy, c = ox * ox + oy * oy - f.half_x * f.half_x;
    if (c <= 0)
      return 0;
    const double disc = b * b - c;
    if (disc < 0 || b > 0)
      return kInf;
    return -b - std::sqrt(disc);
  }
  // Slab test in the rectangle's own frame.
  const double c = std::cos(f.yaw), s = std::sin(f.yaw);
  const double lx = c * ox + s * oy, ly = -s * ox + c * oy;
  const double ldx = c * dx + s * dy, ldy = -s * dx + c * dy;
  double t0 = 0, t1 = kInf;
  const double p[2] = {lx, ly}, d[2] = {ldx, ldy}, h[2] = {f.half_x, f.half_y};
  for (int k = 0; k < 2; ++k)
  {
    if (std::abs(d[k]) < 1e-12)
    {
      if (std::abs(p[k]) > h[k])
        return kInf;
      continue;
    }
    double ta = (-h[k] - p[k]) / d[k], tb = (h[k] - p[k]) / d[k];
    if (ta > tb)
      std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1)
      return kInf;
  }
  return t0;
}
}  // namespace

double distanceTo(const FloorPlan::Footprint& f, double x, double y)
{
  const double dx = x - f.x, dy = y - f.y;
  if (f.disc)
    return std::max(0.0, std::hypot(dx, dy) - f.half_x);
  const double c = std::cos(f.yaw), s = std::sin(f.yaw);
  const double lx = c * dx + s * dy, ly = -s * dx + c * dy;
  return std::hypot(std::max(0.0, std::abs(lx) - f.half_x), std::max(0.0, std::abs(ly) - f.half_y));
}

FloorPlan::FloorPlan(const World& world, double max_height)
{
  for (const auto& o : world.objects())
  {
    if (!o.obstacle || o.position.z() - o.size.z() / 2 > max_height)
      continue;
    Footprint f;
    f.label = o.label;
    f.disc = o.shape == "cylinder";
    f.x = o.position.x();
    f.y = o.position.y();
    f.yaw = f.disc ? 0.0 : o.yaw;
    f.half_x = o.size.x() / 2;
    f.half_y = f.disc ? o.size.x() / 2 : o.size.y() / 2;
    footprints_.push_back(f);
  }
}

double FloorPlan::clearance(double x, double y) const
{
  double best = kInf;
  for (const auto& f : footprints_)
    best = std::min(best, distanceTo(f, x, y));
  return best;
}

std::string FloorPlan::obstacleAt(double x, double y, double radius) const
{
  for (const auto& f : footprints_)
    if (distanceTo(f, x, y) < radius)
      return f.label;
  return "";
}

double FloorPlan::range(double x, double y, double bearing, double max_range) const
{
  const double dx = std::cos(bearing), dy = std::sin(bearing);
  double best = kInf;
  for (const auto& f : footprints_)
    best = std::min(best, rayEntry(f, x, y, dx, dy));
  return best <= max_range ? best : kInf;
}

std::vector<FloorPlan::Sighting> FloorPlan::visible(double x, double y, double heading, double half_fov,
                                                    double max_range) const
{
  std::vector<Sighting> seen;
  for (size_t i = 0; i < footprints_.size(); ++i)
  {
    const Footprint& f = footprints_[i];
    const double d = std::hypot(f.x - x, f.y - y);
    const double b = std::atan2(f.y - y, f.x - x);
    if (d > max_range || std::abs(std::remainder(b - heading, 2 * M_PI)) > half_fov)
      continue;
    // Hidden when something else is met first: along the bearing, the first boundary is nearer than this
    // footprint's own entry (which lies at most its half-diagonal before its centre).
    const double entry = d - std::hypot(f.half_x, f.half_y);
    bool hidden = false;
    for (size_t j = 0; j < footprints_.size() && !hidden; ++j)
      hidden = j != i && rayEntry(footprints_[j], x, y, std::cos(b), std::sin(b)) < std::max(0.0, entry);
    if (!hidden)
      seen.push_back({i, d, b});
  }
  return seen;
}

cv::Mat1b FloorPlan::rasterize(double origin_x, double origin_y, double cell, int rows, int cols) const
{
  cv::Mat1b grid(std::max(rows, 0), std::max(cols, 0), uchar(0));
  if (!(cell > 0))
    return grid;
  for (int r = 0; r < grid.rows; ++r)
    for (int c = 0; c < grid.cols; ++c)
      if (clearance(origin_x + (c + 0.5) * cell, origin_y + (r + 0.5) * cell) <= cell / 2)
        grid(r, c) = 255;
  return grid;
}
}  // namespace biovision_sim
