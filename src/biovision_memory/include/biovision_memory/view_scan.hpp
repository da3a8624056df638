#pragma once

#include <limits>
#include <vector>

#include <Eigen/Core>

namespace biovision_memory
{
/// What one disparity frame says about the floor plane around the robot, in base_link (x forward,
/// y left; bearings [rad], + = left; ranges [m] from base_link's origin on the floor). Made by
/// ViewScanner; consumed by ShortTermMemory (the strips) and LongTermMemory (points and free space).
struct ViewScan
{
  static constexpr float kNone = std::numeric_limits<float>::infinity();

  /// One of the thesis's vertical image strips (§5.3.1: 3 strips of ≈14.3° for a 43° camera).
  struct Strip
  {
    double centre_bearing = 0.0;  ///< bearing of the strip's centre ray (image row cy) [rad]
    float nearest_range = kNone;  ///< range of its nearest obstacle [m]; kNone: no obstacle within max_range
    Eigen::Vector2d nearest_point{0.0, 0.0};  ///< that obstacle's floor position [m] (valid if nearest_range finite)
    bool observed = false;  ///< enough valid disparity to say "nothing near here" (false: blind strip)
  };

  /// Free-space evidence along bearings: bin i covers [bearing_min + i·bin_width, + bin_width).
  struct Bin
  {
    float obstacle_range = kNone;  ///< nearest obstacle [m] in the bin
    /// Nearest range known free [m]: where the ray to the bin's nearest floor point came down to
    /// min_obstacle_height (an obstacle there would have hidden that point), not the point itself —
    /// the floor under the camera's lowest rows is out of view, what stands on it is not.
    float free_from = kNone;
    float free_to = 0.0f;  ///< farthest range known free [m]: min(obstacle, farthest floor point)
    /// Nearest / farthest floor point of the bin [m], as distances from camera_position on the floor (kNone /
    /// 0: no floor seen). A ray to the floor at distance D crosses height h at D·(1 − h/camera_height): what
    /// LongTermMemory uses to tell whether a remembered obstacle of known heights would have been in view.
    float floor_near = kNone;
    float floor_far = 0.0f;
  };

  std::vector<Strip> strips;                     ///< left to right in the image
  double bearing_min = 0.0;                      ///< [rad]
  double bin_width = 0.0;                        ///< [rad]
  std::vector<Bin> bins;                         ///< covers the camera's view
  std::vector<Eigen::Vector3d> obstacle_points;  ///< base_link [m], between the obstacle heights, within range
  Eigen::Vector2d camera_position{0.0, 0.0};     ///< the left camera's floor position in base_link [m]
  double camera_height = 0.0;                    ///< the left camera above the floor [m] (0: unknown)
  double min_obstacle_height = 0.0;              ///< [m] points lower than this were floor (ViewScanParameters)
  double max_range = 0.0;                        ///< [m]
  int valid_pixels = 0;                          ///< pixels with a usable disparity
  int invalid_pixels = 0;                        ///< NaN, ±Inf, ≤ 0 or kInvalid

  /// The bin index of a bearing, −1 outside the scan.
  int binOf(double bearing) const;
};
}  // namespace biovision_memory
