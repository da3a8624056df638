#include "biovision_memory/short_term_memory.hpp"

#include <algorithm>
#include <cmath>

#include "biovision_memory/long_term_memory.hpp"

namespace biovision_memory
{
ShortTermMemory::ShortTermMemory(const ShortTermMemoryParameters& parameters)
  : parameters_(parameters), scanner_(parameters.scan)
{
  parameters_.validate();
  cells_.resize(parameters_.sectors);
}

void ShortTermMemory::setParameters(const ShortTermMemoryParameters& parameters)
{
  parameters.validate();
  ViewScanner scanner(parameters.scan);
  if (parameters.sectors != parameters_.sectors || parameters.sector_width != parameters_.sector_width)
    cells_.assign(parameters.sectors, Cell{});  // the sector layout changed: what was where is gone
  parameters_ = parameters;
  scanner_ = scanner;
  age();
}

void ShortTermMemory::reset()
{
  cells_.assign(parameters_.sectors, Cell{});
  last_scan_ = ViewScan{};
  has_pose_ = false;
  pose_ = Pose2D{};
  stamp_ = 0.0;
}

int ShortTermMemory::sectorOf(double bearing) const
{
  const double half = 0.5 * parameters_.sectors * parameters_.sector_width;
  const double b = Pose2D::normalizeAngle(bearing);
  if (!(b >= -half && b <= half))
    return -1;
  return std::min(parameters_.sectors - 1, static_cast<int>(std::floor((b + half) / parameters_.sector_width)));
}

double ShortTermMemory::sectorCentre(int i) const
{
  return (i + 0.5 - 0.5 * parameters_.sectors) * parameters_.sector_width;
}

bool ShortTermMemory::moveTo(const Pose2D& odom_from_base, double stamp)
{
  bool monotone = true;
  if (has_pose_ && stamp < stamp_)
  {
    reset();
    monotone = false;
  }
  if (!std::isfinite(stamp))
    return monotone;
  if (!odom_from_base.isFinite())
  {
    stamp_ = std::max(stamp_, stamp);
    age();
    return monotone;
  }
  if (has_pose_)
  {
    const Pose2D delta = pose_.inverse().compose(odom_from_base);  // the motion, in the old base frame
    if (delta.x != 0.0 || delta.y != 0.0 || delta.yaw != 0.0)
    {
      const Pose2D old_from_new = delta.inverse();
      const double travelled = std::hypot(delta.x, delta.y);
      std::vector<Cell> moved(parameters_.sectors);
      for (const Cell& c : cells_)
      {
        if (!c.known)
          continue;
        Cell m = c;
        m.point = old_from_new.apply(c.point);
        m.travelled += travelled;
        const int s = sectorOf(std::atan2(m.point.y(), m.point.x()));
        if (s < 0)
          continue;  // left the ±90° field
        Cell& target = moved[s];
        const bool take = !target.known || (m.obstacle && !target.obstacle) ||
                          (m.obstacle && target.obstacle && m.point.norm() < target.point.norm()) ||
                          (!m.obstacle && !target.obstacle && m.seen > target.seen);
        if (take)
          target = m;
      }
      cells_.swap(moved);
    }
  }
  pose_ = odom_from_base;
  has_pose_ = true;
  stamp_ = stamp;
  age();
  return monotone;
}

void ShortTermMemory::age()
{
  for (Cell& c : cells_)
  {
    if (!c.known)
      continue;
    const double horizon = c.obstacle ? parameters_.obstacle_horizon_time : parameters_.free_horizon_time;
    if (stamp_ - c.seen >= horizon || c.travelled >= parameters_.horizon_distance)
      clearCell(c);
  }
}

bool ShortTermMemory::update(const cv::Mat& disparity, const DisparityCamera& camera,
                             const Eigen::Isometry3d& base_from_camera, const Pose2D& odom_from_base, double stamp)
{
  ViewScan scan = scanner_.scan(disparity, camera, base_from_camera);  // throws before anything changes
  const bool monotone = update(scan, odom_from_base, stamp);
  last_scan_ = std::move(scan);
  return monotone;
}

bool ShortTermMemory::update(const ViewScan& scan, const Pose2D& odom_from_base, double stamp)
{
  const bool monotone = moveTo(odom_from_base, stamp);
  std::vector<bool> fresh(cells_.size(), false);
  // The sectors the strips look into are free when their strip saw no obstacle within range. (A strip
  // whose obstacle lies in the neighbouring sector leaves its centre sector as it was: free only up to
  // that obstacle's range, which one value per sector cannot say.)
  for (const ViewScan::Strip& strip : scan.strips)
  {
    const int s = sectorOf(strip.centre_bearing);
    if (s < 0 || !strip.observed || std::isfinite(strip.nearest_range) || fresh[s])
      continue;
    Cell& c = cells_[s];
    c = Cell{};
    c.known = true;
    const double centre = sectorCentre(s);
    c.point = scan.max_range * Eigen::Vector2d(std::cos(centre), std::sin(centre));
    c.seen = stamp_;
    fresh[s] = true;
  }
  for (const ViewScan::Strip& strip : scan.strips)
  {
    if (!std::isfinite(strip.nearest_range))
      continue;
    const int s = sectorOf(std::atan2(strip.nearest_point.y(), strip.nearest_point.x()));
    if (s < 0)
      continue;
    Cell& c = cells_[s];
    if (fresh[s] && c.obstacle && c.point.norm() <= strip.nearest_point.norm())
      continue;
    c = Cell{};
    c.known = true;
    c.obstacle = true;
    c.point = strip.nearest_point;
    c.seen = stamp_;
    fresh[s] = true;
  }
  return monotone;
}

std::vector<ShortTermMemory::Sector> ShortTermMemory::sectors() const
{
  std::vector<Sector> out(cells_.size());
  for (size_t i = 0; i < cells_.size(); ++i)
  {
    Sector& s = out[i];
    const Cell& c = cells_[i];
    s.centre = sectorCentre(static_cast<int>(i));
    if (!c.known)
      continue;
    const double horizon = c.obstacle ? parameters_.obstacle_horizon_time : parameters_.free_horizon_time;
    s.age = std::max(0.0, stamp_ - c.seen);
    s.confidence = std::clamp(std::min(1.0 - s.age / horizon, 1.0 - c.travelled / parameters_.horizon_distance), 0.0,
                              1.0);
    s.obstacle = c.obstacle;
    if (c.obstacle)
    {
      s.distance = c.point.norm();
      // One point per sector stands for a face that may reach the sector's edge nearest the heading.
      s.offset = s.distance * std::sin(std::max(0.0, std::abs(s.centre) - parameters_.sector_width / 2));
    }
  }
  return out;
}

std::vector<ShortTermMemory::Sector> ShortTermMemory::sectors(const LongTermMemory& ltm,
                                                              const Pose2D& map_from_base) const
{
  std::vector<Sector> out = sectors();
  const double radius = parameters_.map_completion_radius;
  // Beyond 1000 km the cell indices would overflow: such a pose is as good as none.
  if (!(radius > 0) || !(std::abs(map_from_base.x) < 1e6) || !(std::abs(map_from_base.y) < 1e6) ||
      !std::isfinite(map_from_base.yaw))
    return out;
  const double cell = ltm.parameters().cell_size;
  const int min_strength = ltm.parameters().rules.initial_strength;
  const double c = std::cos(map_from_base.yaw), s = std::sin(map_from_base.yaw);
  // The cells whose centre can lie within the radius: a square of them around the base.
  const int x0 = ltm.cellIndex(map_from_base.x - radius), x1 = ltm.cellIndex(map_from_base.x + radius);
  const int y0 = ltm.cellIndex(map_from_base.y - radius), y1 = ltm.cellIndex(map_from_base.y + radius);
  for (int ix = x0; ix <= x1; ++ix)
    for (int iy = y0; iy <= y1; ++iy)
    {
      const auto it = ltm.cells().find(LongTermMemory::key(ix, iy));
      if (it == ltm.cells().end() || it->second.strength < min_strength)
        continue;
      const double dx = ltm.cellCentre(ix) - map_from_base.x, dy = ltm.cellCentre(iy) - map_from_base.y;
      const double d = std::hypot(dx, dy);
      if (d > radius)
        continue;
      const double ahead = c * dx + s * dy, left = -s * dx + c * dy;  // in base_link
      const int i = sectorOf(std::atan2(left, ahead));
      if (i < 0)
        continue;
      Sector& sector = out[i];
      const double distance = std::max(0.0, d - cell / 2);
      const double offset = std::max(0.0, std::abs(left) - cell / 2);
      // A farther cell still bounds how near the line ahead the sector's obstacles come.
      if (sector.confidence > 0 && sector.obstacle)
        sector.offset = std::min(sector.offset, offset);
      if (sector.confidence > 0 && sector.distance <= distance)
        continue;
      if (!(sector.confidence > 0 && sector.obstacle))
        sector.offset = offset;
      sector.distance = distance;
      sector.confidence = 1.0;
      sector.obstacle = true;
      sector.age = 0.0;
    }
  return out;
}
}  // namespace biovision_memory
