#pragma once

#include <limits>
#include <string>
#include <vector>

#include "biovision_tasks/occupancy_map.hpp"

namespace biovision_tasks
{
/// What the task manager knows of the world in one cycle: the inputs of every block's functions (thesis
/// §5.3.3: the visuomotor cycle "moves according to new visual input"). Positions in the `map` frame
/// (REP-105) [m], angles [rad] (REP-103, + = left), time [s] on the ROS clock.
struct Percept
{
  struct Pose
  {
    double x = 0, y = 0, yaw = 0;
  };
  /// An object recognised in this cycle's view, or remembered by the object memory.
  struct Object
  {
    std::string label;
    double x = 0, y = 0;    ///< [m], map frame
    double confidence = 0;  ///< [0, 1]: recognition score, or the memory's strength
    double last_seen = 0;   ///< [s]
  };

  double time = 0;  ///< [s]; must not go backwards (the node resets the manager when it does)
  Pose pose;        ///< the robot's base_link in map
  double view_yaw = std::numeric_limits<double>::quiet_NaN();  ///< [rad] where the camera looks, in map; NaN: unknown
  bool pose_valid = false;         ///< false: no localisation this cycle (tf missing); tasks stop the base
  std::vector<Object> seen;        ///< recognised now (`objects` topic, placed in map)
  std::vector<Object> remembered;  ///< in the object/landmark memory (memory/ltm_items)
  OccupancyMap map;                ///< the long-term memory's obstacles (memory/ltm); empty when unknown
  bool base_trapped = false;       ///< the base controller reports no progress (its trap detector)
  bool base_fault = false;         ///< the base stopped itself: watchdog, bumper, stall
  /// The HRI greet behaviour's last action (biovision_hri's hri/action: the recognised gesture's entry in
  /// its `actions` table, e.g. "stop", "return_home") and when it came [s]; "" and -inf before any.
  std::string gesture_action;
  double gesture_action_time = -std::numeric_limits<double>::infinity();
};
}  // namespace biovision_tasks
