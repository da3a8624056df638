#pragma once

#include <string>

#include "biovision_sim/world.hpp"

namespace biovision_sim
{
/// Seeded random room worlds for navigation evaluations (issue 16): a rectangular room of four walls,
/// sometimes a partition wall from one side, and clutter (tables, boxes, bins), with a start pose and a goal
/// at least `min_start_goal` apart. One obstacle is put near the straight line from start to goal so that
/// the direct route is blocked more often than not. A world is kept only when the goal is reachable for a
/// disc of `robot_radius` (breadth-first search on the FloorPlan raster inflated by the radius), start and
/// goal have at least `free_radius` of clearance and the goal is inside no obstacle; else the generator
/// draws again from the same random stream. The same seed always gives the same world. ROS-free.
class RoomWorldGenerator
{
public:
  struct Options
  {
    double min_side = 7.0, max_side = 10.0;  ///< room side lengths [m], each drawn uniformly
    int min_clutter = 4, max_clutter = 8;    ///< tables, boxes and bins besides the walls
    double partition_probability = 0.35;     ///< chance of a partition wall [0, 1]
    double min_start_goal = 4.0;             ///< [m] straight-line distance from start to goal
    double robot_radius = 0.26;              ///< [m] the Pioneer 3DX footprint (DifferentialDrive::Limits)
    double free_radius = 0.6;                ///< [m] clearance of start and goal from every footprint
    double raster_cell = 0.05;               ///< [m] cell of the reachability check
    int max_attempts = 200;                  ///< draws before giving up

    /// Throws std::invalid_argument naming the field: sides outside (2, 50] or min > max, clutter counts
    /// outside [0, 50] or min > max, probability outside [0, 1], non-positive distances, a room too small
    /// for min_start_goal, max_attempts < 1.
    void validate() const;
  };

  /// A generated world with the start pose and the goal (world frame, metres and radians).
  struct Room
  {
    World world;
    unsigned seed = 0;
    double width = 0, depth = 0;  ///< room extent along x and y [m]; the room spans [0, width] x [-depth/2, depth/2]
    double start_x = 0, start_y = 0, start_yaw = 0;
    double goal_x = 0, goal_y = 0;
    int attempts = 0;  ///< draws it took (1 = the first was kept)
  };

  /// With the default options.
  RoomWorldGenerator();
  /// Throws std::invalid_argument (Options::validate).
  explicit RoomWorldGenerator(const Options& options);

  /// The room of `seed`. Throws std::runtime_error when max_attempts draws all fail (the options make
  /// reachable rooms too unlikely).
  Room generate(unsigned seed) const;

  const Options& options() const { return options_; }

private:
  Options options_;
};
}  // namespace biovision_sim
