#include "biovision_memory/long_term_memory.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace biovision_memory
{
void LongTermMemoryParameters::validate() const
{
  rules.validate();
  auto fail = [](const char* field, double value, const char* range) {
    std::ostringstream m;
    m << "LongTermMemoryParameters." << field << " = " << value << " is outside " << range;
    throw std::invalid_argument(m.str());
  };
  if (!(cell_size >= 0.02 && cell_size <= 1.0))
    fail("cell_size", cell_size, "[0.02, 1]");
  if (min_points < 1 || min_points > 1000)
    fail("min_points", min_points, "[1, 1000]");
  if (!(free_margin >= 0.0 && free_margin <= 2.0))
    fail("free_margin", free_margin, "[0, 2]");
}

LongTermMemory::LongTermMemory(const LongTermMemoryParameters& parameters) : parameters_(parameters)
{
  parameters_.validate();
}

void LongTermMemory::setParameters(const LongTermMemoryParameters& parameters)
{
  parameters.validate();
  const bool resize = parameters.cell_size != parameters_.cell_size;
  parameters_ = parameters;
  if (resize)
    clear();
}

int LongTermMemory::cellIndex(double v) const
{
  return static_cast<int>(std::floor(v / parameters_.cell_size));
}

const LongTermMemory::Cell* LongTermMemory::cellAt(double x, double y) const
{
  const auto it = cells_.find(key(cellIndex(x), cellIndex(y)));
  return it == cells_.end() ? nullptr : &it->second;
}

void LongTermMemory::erase(std::unordered_map<std::int64_t, Cell>::iterator it)
{
  removed_.emplace_back(it->second.ix, it->second.iy);
  dirty_.erase(it->first);
  cells_.erase(it);
}

int LongTermMemory::forget(double stamp)
{
  if (!std::isfinite(stamp))
    return 0;
  int removed = 0;
  for (auto it = cells_.begin(); it != cells_.end();)
  {
    Cell& c = it->second;
    const double before = c.last_change;
    c.strength = parameters_.rules.decay(c.strength, c.last_change, stamp);
    if (c.strength <= 0)
    {
      auto next = std::next(it);
      erase(it);
      it = next;
      ++removed;
      continue;
    }
    if (c.last_change != before)
      touch(it->first);
    ++it;
  }
  return removed;
}

void LongTermMemory::observe(double x, double y, double stamp, float top)
{
  const int ix = cellIndex(x), iy = cellIndex(y);
  const std::int64_t k = key(ix, iy);
  auto it = cells_.find(k);
  if (it == cells_.end())
  {
    Cell c;
    c.ix = ix;
    c.iy = iy;
    c.strength = parameters_.rules.initial_strength;
    c.observations = 1;
    c.first_seen = c.last_seen = c.last_change = stamp;
    c.top = top;
    cells_.emplace(k, c);
  }
  else
  {
    Cell& c = it->second;
    c.strength = parameters_.rules.reinforce(c.strength);
    ++c.observations;
    c.last_seen = c.last_change = stamp;
    c.top = std::fmax(c.top, top);  // fmax skips a NaN: the highest of the sightings with heights
  }
  touch(k);
}

bool LongTermMemory::inViewByHeight(const ViewScan& scan, const ViewScan::Bin& bin, const Cell& cell,
                                    const Eigen::Vector2d& base_point)
{
  // A ray to the floor at distance D from the camera crosses height h at D·(1 − h/H). An obstacle is taken to
  // stand on the floor, as free_from does: the cell's column from min_obstacle_height to its top is crossed
  // by the rays landing in [r·H/(H − min_obstacle_height), r·H/(H − top)]. The top 5 cm are left out: a ray
  // through the cell's centre that low still passes over a face at the cell's near edge.
  constexpr double kTopMargin = 0.05;
  const double H = scan.camera_height, bottom = std::max(0.0, scan.min_obstacle_height);
  const double top = cell.top - kTopMargin;
  if (!std::isfinite(cell.top) || !(H > top) || !(top > bottom) || !std::isfinite(bin.floor_near))
    return false;
  const double r = (base_point - scan.camera_position).norm();
  const double nearest_landing = r * H / (H - bottom), farthest_landing = r * H / (H - top);
  return farthest_landing >= bin.floor_near && nearest_landing <= bin.floor_far;
}

LongTermMemory::UpdateStats LongTermMemory::update(const ViewScan& scan, const Pose2D& map_from_base, double stamp)
{
  UpdateStats stats;
  if (!map_from_base.isFinite() || !std::isfinite(stamp))
    return stats;
  stats.removed += forget(stamp);
  // (a) cells with enough obstacle points this frame.
  struct Points
  {
    int n = 0;
    float top = -std::numeric_limits<float>::infinity();
  };
  std::unordered_map<std::int64_t, Points> counts;
  for (const Eigen::Vector3d& p : scan.obstacle_points)
  {
    const Eigen::Vector2d m = map_from_base.apply(p.head<2>());
    Points& c = counts[key(cellIndex(m.x()), cellIndex(m.y()))];
    ++c.n;
    c.top = std::max(c.top, static_cast<float>(p.z()));
  }
  std::unordered_set<std::int64_t> seen;
  for (const auto& [k, points] : counts)
  {
    if (points.n < parameters_.min_points)
      continue;
    const int ix = static_cast<int>(k >> 32), iy = static_cast<int>(static_cast<std::int32_t>(k & 0xffffffff));
    const bool existed = cells_.count(k) > 0;
    observe(cellCentre(ix), cellCentre(iy), stamp, points.top);
    (existed ? stats.reinforced : stats.added)++;
    seen.insert(k);
  }
  // (b) remembered cells in view, nearer than what the frame saw free along their bearing.
  const Pose2D base_from_map = map_from_base.inverse();
  for (auto it = cells_.begin(); it != cells_.end();)
  {
    Cell& c = it->second;
    if (seen.count(it->first))
    {
      ++it;
      continue;
    }
    const Eigen::Vector2d b = base_from_map.apply({cellCentre(c.ix), cellCentre(c.iy)});
    const double range = b.norm();
    const int bin = scan.binOf(std::atan2(b.y(), b.x()));
    if (bin < 0 || range > scan.max_range)
    {
      ++it;
      continue;
    }
    const ViewScan::Bin& v = scan.bins[bin];
    if ((range >= v.free_from || inViewByHeight(scan, v, c, b)) && range < v.free_to - parameters_.free_margin)
    {
      c.strength = parameters_.rules.weaken(c.strength);
      c.last_change = stamp;
      ++stats.weakened;
      if (c.strength <= 0)
      {
        auto next = std::next(it);
        erase(it);
        it = next;
        ++stats.removed;
        continue;
      }
      touch(it->first);
    }
    ++it;
  }
  return stats;
}

void LongTermMemory::clear()
{
  for (const auto& [k, c] : cells_)
    removed_.emplace_back(c.ix, c.iy);
  cells_.clear();
  dirty_.clear();
}

void LongTermMemory::load(const std::vector<Cell>& cells)
{
  for (const Cell& c : cells)
    cells_[key(c.ix, c.iy)] = c;
}

void LongTermMemory::rebaseTime(double now)
{
  for (auto& [k, c] : cells_)
  {
    if (c.last_change > now || c.last_seen > now || c.first_seen > now)
    {
      c.last_change = std::min(c.last_change, now);
      c.last_seen = std::min(c.last_seen, now);
      c.first_seen = std::min(c.first_seen, now);
      touch(k);
    }
  }
}

LongTermMemory::Changes LongTermMemory::takeChanges()
{
  Changes changes;
  changes.upserted.reserve(dirty_.size());
  for (std::int64_t k : dirty_)
  {
    const auto it = cells_.find(k);
    if (it != cells_.end())
      changes.upserted.push_back(it->second);
  }
  changes.removed.swap(removed_);
  dirty_.clear();
  return changes;
}
}  // namespace biovision_memory
