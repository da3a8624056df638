#pragma once

#include <string>

namespace biovision_tasks
{
/// What the active visuomotor cycle asks of the head and the base in one cycle (thesis §5.3.3: only one
/// visuomotor block drives the robot at a time). The node turns it into the head controller's mode
/// (biovision_msgs/SetHeadMode) and the base controller's goal. The default is safe: base stopped.
struct MotorCommand
{
  enum class Base
  {
    Stop,     ///< zero speed
    Goal,     ///< drive to (goal_x, goal_y) [m, map], around obstacles (base attractor dynamics)
    Heading,  ///< turn in place to `heading` [rad, map]
  };
  Base base = Base::Stop;
  double goal_x = 0, goal_y = 0;  ///< [m], map frame
  double heading = 0;             ///< [rad], map frame

  /// Head controller mode: "explore", "track", "look_ahead", "hold"; "" = leave it as it is.
  std::string head_mode;
  std::string head_target;  ///< with "track": the object label

  /// Navigation mode (thesis §5.3.3): "exploration" (unknown area) or "excursion" (planned over the LTM).
  std::string mode;

  /// Ask biovision_hri to look up, centre a face and read a gesture (hri/greet; thesis §2.1); the node
  /// calls hri/stop_greet when it turns false again. The HRI behaviour holds the head meanwhile.
  bool greet = false;
};
}  // namespace biovision_tasks
