#pragma once

#include <string>
#include <vector>

#include "biovision_attractor/base_attractor_parameters.hpp"
#include "biovision_attractor/head_attractor_parameters.hpp"
#include "biovision_memory/short_term_memory_parameters.hpp"
#include "biovision_tasks/occupancy_map.hpp"
#include "biovision_tasks/task_parameters.hpp"

namespace biovision_tasks
{
/// The thesis's ch. 5 experiment as one closed-loop trial without ROS (mission_eval): in a seeded random
/// room (biovision_sim::RoomWorldGenerator) a labelled target box stands where the generator put the goal,
/// behind the robot at the start (out of its view); the TaskManager runs "search target; return_home";
/// once the target is found, new obstacles are put on the straight way home (the LTM does not know them).
///
/// The loop: the simulator's DifferentialDrive and pan Servo; the head's HeadAttractor (explore or
/// look_ahead, as the task asks; salient regions = the clutter in view, the stand-in of the navigation
/// eval); the base's BaseAttractor; biovision_memory's ShortTermMemory and LongTermMemory fed with a
/// ViewScan made from the FloorPlan's ranges across the camera's view (ground-truth ranges, not stereo: the
/// memory eval measures the stereo path); recognition is an oracle: the target counts as recognised when
/// its centre is in the camera's view, within recognition_range and not hidden, at its true position plus
/// Gaussian noise. Odometry is exact (map = odom).
struct MissionTrialOptions
{
  double timeout = 600.0;          ///< [s] of simulated time for the whole mission
  double physics_rate = 50.0;      ///< [Hz]
  double control_rate = 10.0;      ///< [Hz] base and head
  double perception_rate = 5.0;    ///< [Hz] STM/LTM updates, recognition and task cycles (the camera loop)
  double horizontal_fov = 0.7505;  ///< [rad] Bumblebee-2 (thesis L948)
  double max_range = 3.0;          ///< [m] of the view scan
  double recognition_range = 3.0;  ///< [m] the oracle recognises the target within this
  double position_noise = 0.1;     ///< [m] standard deviation of the recognised position
  int new_obstacles = 2;           ///< put on the way home once the target is found
  double servo_speed = 3.0;        ///< [rad/s]
  biovision_memory::ShortTermMemoryParameters stm;  ///< the STM's (mission_eval --set stm.NAME=VALUE)
  /// A world file (biovision_sim's YAML, e.g. the demo's corridor.yaml) instead of the generated rooms: the
  /// target where its object labelled world_target stands (that object taken out), the robot at the origin
  /// facing +x as in the demo, moved by up to start_jitter m across and start_jitter rad per seed; the world
  /// must lie within x in [-1, 11] m, y in [-5, 5] m (the LTM map's extent); one new obstacle at most, placed
  /// by the demo's rule (mission_director). Empty: generated rooms.
  std::string world_file;
  std::string world_target = "target_box";
  double start_jitter = 0.3;
};

/// One contact of the base with the world, and what the loop believed at that moment (mission_eval's JSON).
struct MissionCollision
{
  double time = 0;             ///< [s]
  cv::Point2d position;        ///< [m] map frame
  std::string object;          ///< the footprint hit (the world object's label)
  std::string task;            ///< the macro-task then driving
  std::string base_status;     ///< BaseAttractor::name of the last control step
  double linear = 0;           ///< [m/s] commanded at the last control step
  double angular = 0;          ///< [rad/s] commanded at the last control step
  double front_clearance = 0;  ///< [m] the STM's clearance in the swept corridor ahead (+Inf: none known)
  double pan = 0;              ///< [rad] where the camera looked
  double contact_bearing = 0;  ///< [rad, base_link, + = left] of the nearest footprint point at the contact
  double stm_distance = 0;     ///< [m] the STM sector holding that bearing: its obstacle distance (+Inf: none)
  double stm_confidence = 0;   ///< [0, 1] that sector's confidence (0: unknown)
};

struct MissionTrialResult
{
  unsigned seed = 0;
  bool found = false;
  double found_time = 0;           ///< [s]
  double found_error = 0;          ///< [m] recorded target position vs the truth
  bool returned = false;           ///< the mission's return_home succeeded
  double final_home_distance = 0;  ///< [m]
  bool completed = false;          ///< found and returned
  int collisions = 0;
  int new_obstacles_placed = 0;
  double time = 0;           ///< [s] until the task buffer emptied (or the timeout)
  double path_length = 0;    ///< [m]
  double min_clearance = 0;  ///< [m] between the base's disc and any footprint
  int ltm_cells = 0;         ///< obstacle cells in the LTM at the end
  double ltm_precision = 0;  ///< LTM cells on a true footprint (within one cell) / LTM cells
  std::string outcome;       ///< the task manager's last finished-task reasons
  // For the trial's picture (mission_eval --plots): map frame, metres.
  std::vector<cv::Point2d> path;  ///< the base's positions, every 5 cm
  cv::Point2d home, target, target_found{NAN, NAN};
  std::vector<cv::Point2d> new_obstacle_positions, collision_positions;
  std::vector<MissionCollision> collision_details;
  OccupancyMap ltm;  ///< the LTM at the end, strength 0..100
};

/// Checks o.world_file before any trial: a regular file of at most 1 MiB that parses, at most 100 objects, all
/// finite with centres within 0.5 m of the LTM map's extent, exactly one object labelled o.world_target, at most 1 m wide, inside the LTM map's
/// extent, standing free and 1 m + start_jitter from the start, and a start (any jitter) 0.3 m clear of every
/// object. Throws std::runtime_error saying which (nothing to check without a world).
void checkMissionWorld(const MissionTrialOptions& o);

/// Runs the mission of `seed`. Throws std::invalid_argument for bad parameters, std::runtime_error for a
/// world file checkMissionWorld refuses.
MissionTrialResult runMissionTrial(unsigned seed, const TaskParameters& tasks,
                                   const biovision_attractor::BaseAttractorParameters& base,
                                   const biovision_attractor::HeadAttractorParameters& head,
                                   const MissionTrialOptions& options);
}  // namespace biovision_tasks
