#pragma once

#include <string>
#include <utility>
#include <vector>

namespace biovision_tasks
{
/// Constants of the task manager's simple macro-tasks (thesis §5.3.3 gives none: each is a [gap] filled
/// here, with the reason). Units SI; every field is a parameter of the task_manager node.
struct TaskParameters
{
  double goal_tolerance = 0.3;     ///< [m] a place is reached within this (issue #16's navigation goal)
  double approach_distance = 0.9;  ///< [m] "go to <object>" stops this far from its centre: the base is 0.26 m
                                   ///< in radius, the base controller's safety stop 0.35 m, plus the object's half size
  double waypoint_tolerance = 0.5;  ///< [m] a waypoint of the planned path counts as passed within this
  double robot_radius = 0.26;       ///< [m] the Pioneer 3DX's footprint (simulator and URDF)
  double inflation_margin = 0.15;   ///< [m] added to the radius when planning over the LTM
  /// [m] the least clearance beyond the radius a plan keeps when no path keeps inflation_margin (GridPlanner's
  /// squeeze pass; >= inflation_margin: none): the base's corridor_margin, so that the base drives what is
  /// planned (its swept corridor is robot_radius + 0.1; with 0.05 it stopped "blocked" beside a crate for 80 s
  /// in make demo). mission_eval 101-1300 completed: 0.05 1153, 0.10 1157, 0.12 1162.
  double squeeze_margin = 0.10;
  int occupied_threshold = 40;   ///< [0..100] LTM strength (100·strength/M_R) that blocks planning: 40 = 80 of
                                 ///< M_R 200, two sightings net (one is 20); phantoms fade below it
  double replan_period = 4.0;    ///< [s] excursions replan over the LTM this often (it keeps changing)
  double explore_step = 1.5;     ///< [m] exploration picks goals this far away ...
  double explore_period = 12.0;  ///< [s] ... and a new one at least this often
  /// [s] at each new exploration goal the base stops and the head explores this long; while driving the
  /// head then looks ahead, so the base never drives where the camera is not looking (0 = the head explores
  /// all the time, the thesis's way: 17 collisions in mission_eval's 10 report rooms)
  double look_time = 6.0;
  double visit_cell = 0.5;  ///< [m] cell of the exploration's visit counts (boredom) and of its coverage
  /// [m] a cell this near the camera, inside its view and in sight over the LTM, counts as seen; exploration
  /// heads for the nearest frontier of what was seen (Yamauchi 1997) and wanders by boredom once none is left
  /// (0: boredom only, the previous strategy). mission_eval's tune seeds 101-160, missions completed without a
  /// collision: 0: 40/60; 1.5/2.0/2.5/3.0 m: 38/44/45/45 (a noisy optimum: 2.5 m had the fewest collisions)
  double view_range = 2.5;
  double view_angle =
      0.75;  ///< [rad] the view about the camera's heading that counts as seen: the Bumblebee-2's 0.75 rad
  /// [s] a frontier the base could not reach is tried again after this, twice as long after each further
  /// failure (ExplorationPlanner::markUnreachable; before: never again)
  double frontier_retry_time = 60.0;
  double home_range_cost = 0.1;   ///< [s of boredom per m] goals far from home cost more, so the robot covers the area
                                  ///< round home before wandering off in a straight line; 0.1 completed the
                                  ///< most missions on mission_eval's tune seeds 101-110 (0.1/0.3/0.5 gave 7/7/4)
  double trapped_timeout = 40.0;  ///< [s] a base trapped (or faulted) this long fails the task (return_home:
                                  ///< retraces the trail driven first, GoToTask). 40: the demo's corridor world,
                                  ///< tune seeds 101-500, completed 318 / 344 / 349 / 351 / 343 of 400 at
                                  ///< 20 / 30 / 40 / 50 / 60 s; the rooms' 101-1300 the same at 20, 30, 40 s
  double stall_time = 15.0;     ///< [s] driving without moving stall_distance this long counts as trapped, whatever the
                                ///< base says: longer than the base's own trap_time (12 s), whose clock each new goal
                                ///< (a replanned waypoint) restarts
  double stall_distance = 0.3;  ///< [m]
  double min_memory_confidence = 0.4;  ///< [0..1] a remembered object this strong is worth an excursion
  /// [m] `search` concludes on a second sighting this near the first (0: on the first). Why: single
  /// recognitions of the target on the corridor's walls (3 of 751 `objects` messages in a mission.test
  /// run, none repeated) ended searches at a wrong place; the real target is named frame after frame.
  double confirm_distance = 2.0;
  double confirm_time = 10.0;  ///< [s] the second sighting comes at most this long after the first
  /// [s] default time-out of `search` (mission_eval tune seeds 101-300: 240 / 300 / 360 s completed 177 / 185 / 185)
  double search_timeout = 300.0;
  /// [s] default time-out of `greet`: the HRI behaviour's face search (8 s), centring and gesture wait
  /// (15 s) fit in it (biovision_hri's defaults).
  double greet_timeout = 30.0;
  /// [m] an LTM obstacle this near in front (within +-kGreetCone of the heading) while the base drives
  /// starts a `greet` above the active task, which resumes afterwards (thesis §2.1: an obstacle in front
  /// may be a person); 0 = never (the default: the find-and-return mission has nobody to meet).
  double greet_distance = 0.0;
  /// [s] after a greet ends, obstacles in front start none for this long (a wall stays in front).
  double greet_cooldown = 60.0;
  static constexpr double kGreetCone = 0.35;  ///< [rad] half-angle of "in front"
  double go_to_timeout = 240.0;               ///< [s] default time-out of `go_to` and `return_home`

  /// Throws std::invalid_argument naming the field and its range.
  void validate() const;
  /// The fields by their parameter name (config/task_manager.yaml, cfg/TaskManager.cfg).
  static const std::vector<std::pair<std::string, double TaskParameters::*>>& namedDoubles();
  static const std::vector<std::pair<std::string, int TaskParameters::*>>& namedInts();
};
}  // namespace biovision_tasks
