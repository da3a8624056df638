#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_sim/world.hpp"

namespace biovision_sim
{
/// The ground truth a mobile base meets: the 2-D footprints (on the floor plane, world frame x/y [m]) of the
/// world's obstacles, with the geometric queries that evaluation tools need — clearance, contact, range along
/// a bearing and an occupancy raster. Cylinders are discs, boxes oriented rectangles (their yaw).
/// Objects with `obstacle: false` and objects whose bottom is above `max_height` (a robot passes under them)
/// are not in the plan. ROS-free; nothing throws.
class FloorPlan
{
public:
  /// The robot with its mast is 1.2 m tall (biovision_description): objects whose bottom is higher pass over it.
  static constexpr double kDefaultMaxHeight = 1.2;

  struct Footprint
  {
    std::string label;
    bool disc = false;    ///< true: a disc of radius half_x; false: a rectangle
    double x = 0, y = 0;  ///< centre [m]
    double yaw = 0;       ///< rectangle orientation [rad]
    double half_x = 0;    ///< half extent along the rectangle's own x (disc: radius) [m]
    double half_y = 0;    ///< half extent along its own y [m]
  };

  explicit FloorPlan(const World& world, double max_height = kDefaultMaxHeight);

  const std::vector<Footprint>& footprints() const { return footprints_; }

  /// Distance [m] from (x, y) to the nearest footprint's boundary; 0 inside one; +Inf when the plan is empty.
  double clearance(double x, double y) const;
  /// The label of a footprint a disc of `radius` [m] at (x, y) overlaps (clearance < radius), or "".
  std::string obstacleAt(double x, double y, double radius) const;
  /// Distance [m] along the ray from (x, y) in direction `bearing` [rad, world frame] to the first footprint
  /// boundary it meets, +Inf when none within `max_range` [m]; 0 when (x, y) is inside a footprint.
  double range(double x, double y, double bearing, double max_range) const;
  /// Occupancy raster: cell (r, c) covers x in [origin_x + c·cell, +cell), y in [origin_y + r·cell, +cell)
  /// (row 0 = smallest y, the nav_msgs/OccupancyGrid layout); 255 where the cell's centre is inside a
  /// footprint or within half a cell of one, else 0. cell > 0, rows/cols ≥ 0.
  cv::Mat1b rasterize(double origin_x, double origin_y, double cell, int rows, int cols) const;

  /// A footprint a viewer sees: its index in footprints(), the distance [m] and world bearing [rad] of its centre.
  struct Sighting
  {
    size_t index = 0;
    double distance = 0, bearing = 0;
  };
  /// The footprints whose centre a viewer at (x, y) looking along `heading` [rad, world] sees: within
  /// `half_fov` [rad] of the heading, within `max_range` [m], and not hidden — the first boundary along the
  /// bearing is the footprint's own (no other footprint nearer on the line of sight). The ground truth of
  /// what a camera can recognise or find salient (evaluation tools).
  std::vector<Sighting> visible(double x, double y, double heading, double half_fov, double max_range) const;

private:
  std::vector<Footprint> footprints_;
};

/// Distance [m] from (x, y) to one footprint's boundary (0 inside).
double distanceTo(const FloorPlan::Footprint& f, double x, double y);
}  // namespace biovision_sim
