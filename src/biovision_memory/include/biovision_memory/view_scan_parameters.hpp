#pragma once

namespace biovision_memory
{
/// How ViewScanner turns a disparity map into obstacles and free floor (thesis §5.3.1 thresholds the
/// disparity at "20% of the maximum disparity"; that reading is ambiguous, so the threshold is a
/// distance: a point is an obstacle when it lies within `max_range` of the robot and between the two
/// heights above the floor).
struct ViewScanParameters
{
  /// Obstacle range threshold [m], (0.3, 20]. Replaces the thesis's "20 % of the maximum disparity": with
  /// the Bumblebee-2 model at 320 px (fx ≈ 406 px, B = 0.12 m) disparity 64 · 0.2 ≈ 13 px is Z ≈ 3.8 m;
  /// 3 m keeps the BioBin depth error (≈ 0.1 m at 3 m for 0.5 px) within a 0.1 m map cell's reach.
  double max_range = 3.0;
  /// A point lower than this above the floor is floor [m], [0, 1). BioBin's floor points scatter in
  /// height; memory_eval (room, tune split) measured LTM precision 0.66 at 0.15 m and 0.60 at 0.08 m with
  /// the same misses (none).
  double min_obstacle_height = 0.15;
  /// A point higher than this passes over the robot [m] (the robot with its mast is 1.2 m tall),
  /// (min_obstacle_height, 5].
  double max_obstacle_height = 1.2;
  /// Vertical image strips (thesis: 3), [1, 15].
  int strips = 3;
  /// A strip's nearest obstacle is its k-th nearest obstacle pixel (k = this), which rejects
  /// isolated mismatches, [1, 1000].
  int min_obstacle_pixels = 8;
  /// A strip with fewer valid pixels than this fraction is blind (reports neither obstacle nor free
  /// space), [0, 1].
  double min_valid_fraction = 0.2;
  /// Width of a free-space bin [rad], [0.002, 0.2] (≈ 1°).
  double bin_width = 0.0175;
  /// Every n-th pixel in each direction is projected, [1, 8] (2 keeps 1/4 of 320×240).
  int pixel_step = 2;

  /// Throws std::invalid_argument naming the offending field and its range.
  void validate() const;
};
}  // namespace biovision_memory
