#pragma once

#include <cstdint>
#include <limits>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "biovision_memory/pose2d.hpp"
#include "biovision_memory/reinforcement_rules.hpp"
#include "biovision_memory/view_scan.hpp"

namespace biovision_memory
{
/// Parameters of the long-term map (thesis §5.3.2; cell size, "same place" and "expected" are gaps).
struct LongTermMemoryParameters
{
  ReinforcementRules rules;  ///< P_R, M_R, N_R, t_LTM and the initial strength
  /// Map cell [m], [0.02, 1]. Lower resolution than the STM (thesis); 0.1 m is the BioBin depth error at
  /// 3 m (0.5 px) — a cell is "the same place".
  double cell_size = 0.1;
  /// A cell is seen in a frame when at least this many obstacle points (of the scan's every-2nd pixel)
  /// fall into it, [1, 1000]: stereo mismatches scatter a few points; memory_eval (room, tune split)
  /// measured LTM precision 0.66 / 0.77 / 0.85 / 0.89 at 3 / 6 / 12 / 20 with recall 1.0.
  int min_points = 20;
  /// A remembered cell is "expected but not seen" when it lies in view nearer than the free range along
  /// its bearing by more than this [m], [0, 2] (two cells: the depth error must not erase a wall's own cells).
  double free_margin = 0.2;

  /// Throws std::invalid_argument naming the offending field and its range.
  void validate() const;
};

/// The long-term memory of thesis §5.3.2: a 2-D grid in the `map` frame whose cells hold obstacles with
/// a strength and time tags, reinforced when seen again, weakened when expected but not seen and by time,
/// fixed at M_R and removed at ≤ 0 (ReinforcementRules). Fed with ViewScans placed by the base's map pose.
/// Tracks what changed for incremental saving (MemoryDatabase). Not thread-safe.
class LongTermMemory
{
public:
  struct Cell
  {
    int ix = 0, iy = 0;              ///< cell indices: x in [ix·cell, (ix+1)·cell) [m], map frame
    int strength = 0;                ///< 0 … M_R
    std::uint32_t observations = 0;  ///< sightings
    double first_seen = 0.0;         ///< [s]
    double last_seen = 0.0;          ///< [s]
    double last_change = 0.0;        ///< last reinforcement, penalty or decay step [s] (rule (c) counts from it)
    /// The highest obstacle point seen in the cell [m above the floor]; NaN: unknown (a cell loaded from the
    /// database or marked by observe() without it). Not persisted.
    float top = std::numeric_limits<float>::quiet_NaN();
  };
  struct UpdateStats
  {
    int added = 0, reinforced = 0, weakened = 0, removed = 0;
  };
  /// What changed since the last takeChanges(): cells to write and cells to delete.
  struct Changes
  {
    std::vector<Cell> upserted;
    std::vector<std::pair<int, int>> removed;
  };

  /// Throws std::invalid_argument on bad parameters.
  explicit LongTermMemory(const LongTermMemoryParameters& parameters = {});
  /// Validates first (on a throw nothing changes). A new cell size empties the map (cells cannot be resized).
  void setParameters(const LongTermMemoryParameters& parameters);
  const LongTermMemoryParameters& parameters() const { return parameters_; }

  /// One frame: `scan` was taken with base_link at `map_from_base` at `stamp` [s]. Applies rule (c) to
  /// every cell, then (a) to the cells seen and (b) to remembered cells in view and nearer than the free
  /// range. In view: beyond the bin's free_from (the floor seen there); for a cell of known top also where a
  /// ray to the bin's floor (floor_near … floor_far) crosses it between min_obstacle_height and its top —
  /// nearer than free_from, where the camera does not see the floor but would see what stood there (a
  /// phantom, or a moved object 1.2 m ahead of a camera 1.1 m up). A non-finite pose or stamp is ignored.
  UpdateStats update(const ViewScan& scan, const Pose2D& map_from_base, double stamp);
  /// Rule (c) alone (no frame), e.g. on a timer. Returns the number of cells removed.
  int forget(double stamp);
  /// Marks a cell seen once at `stamp` (as update() does for a cell with enough points), its highest obstacle
  /// point at `top` [m] (NaN: not known; the cell keeps the highest seen).
  void observe(double x, double y, double stamp, float top = std::numeric_limits<float>::quiet_NaN());

  const std::unordered_map<std::int64_t, Cell>& cells() const { return cells_; }
  const Cell* cellAt(double x, double y) const;
  int cellIndex(double v) const;
  double cellCentre(int i) const { return (i + 0.5) * parameters_.cell_size; }

  /// Clears the map (all cells are reported removed by the next takeChanges()).
  void clear();
  /// Loads cells (from the database) without marking them changed.
  void load(const std::vector<Cell>& cells);
  /// Clamps every time tag to ≤ now (the clock jumped back: forgetting restarts from now).
  void rebaseTime(double now);
  Changes takeChanges();

  static std::int64_t key(int ix, int iy)
  {
    // Shifted as unsigned: a negative index shifted as signed is undefined behaviour (the same bits result).
    return static_cast<std::int64_t>((static_cast<std::uint64_t>(static_cast<std::uint32_t>(ix)) << 32) |
                                     static_cast<std::uint32_t>(iy));
  }

private:
  /// Whether a ray of `bin` to its floor crosses `cell` (at base_point [m, base_link]) between the scan's
  /// min_obstacle_height and the cell's top.
  static bool inViewByHeight(const ViewScan& scan, const ViewScan::Bin& bin, const Cell& cell,
                             const Eigen::Vector2d& base_point);
  void touch(std::int64_t k) { dirty_.insert(k); }
  void erase(std::unordered_map<std::int64_t, Cell>::iterator it);

  LongTermMemoryParameters parameters_;
  std::unordered_map<std::int64_t, Cell> cells_;
  std::unordered_set<std::int64_t> dirty_;
  std::vector<std::pair<int, int>> removed_;
};
}  // namespace biovision_memory
