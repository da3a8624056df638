#pragma once

#include <cmath>

#include "biovision_memory/view_scan_parameters.hpp"

namespace biovision_memory
{
/// Parameters of the egocentric short-term memory (thesis §5.3.1). The thesis gives the sectors and
/// strips; how long an out-of-view sector is kept is a gap the horizons fill.
struct ShortTermMemoryParameters
{
  ViewScanParameters scan;  ///< disparity → obstacles (the thresholds)
  int sectors = 9;          ///< thesis: 9, [1, 36]; they tile [−sectors·width/2, +sectors·width/2]
  double sector_width = 20.0 * M_PI / 180.0;  ///< [rad] thesis: 20°, (0, 2π/sectors]
  /// An obstacle not seen again is dropped after this long [s], (0, 600]. Obstacles are kept rather
  /// than forgotten: a base turning away still needs the table it just passed.
  double obstacle_horizon_time = 10.0;
  /// Free space not seen again is unknown after this long [s], (0, 600]: stale free space must never be
  /// reported as fresh, so it fades faster than obstacles.
  double free_horizon_time = 3.0;
  /// Anything not seen again is dropped after the base moved this far [m], (0, 100] (odometry drifts). 3 m, not
  /// 2: an obstacle seen 2 m ahead was forgotten as the base came alongside it, out of view, and the base hit it
  /// (biovision_tasks' mission_eval, make demo's corridor world, tune seeds 101-500: 2 / 2.5 / 3 / 4 m completed
  /// 349 / 349 / 353 / 353 of 400 with 31 / 27 / 23 / 23 collisions; the rooms' 101-1300 1196 -> 1197, 5 -> 4).
  double horizon_distance = 3.0;
  /// Beyond the thesis: the sectors the base reads (memory/stm) also hold the long-term map's obstacles
  /// within this radius [m] of the base, [0, 10] (0: the STM alone, as the thesis). The camera sees ±21°
  /// ahead, so what the base passes leaves the view at its side, where the STM forgets it or never had it;
  /// every collision of mission_eval's tune rooms 101-300 was there (46 in 200 missions). Chosen on rooms
  /// 101-500 among 0.5/0.6/0.7/0.8 m (most missions completed without a collision: 327 of 400 against 292
  /// with 0; collisions 88 → 1; docs/benchmarks.md, mission). ShortTermMemory::sectors(ltm, …) applies it.
  double map_completion_radius = 0.6;

  /// Throws std::invalid_argument naming the offending field and its range.
  void validate() const;
};
}  // namespace biovision_memory
