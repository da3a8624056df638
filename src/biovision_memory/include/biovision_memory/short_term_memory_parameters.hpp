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
  /// Anything not seen again is dropped after the base moved this far [m], (0, 100] (odometry drifts).
  double horizon_distance = 2.0;

  /// Throws std::invalid_argument naming the offending field and its range.
  void validate() const;
};
}  // namespace biovision_memory
