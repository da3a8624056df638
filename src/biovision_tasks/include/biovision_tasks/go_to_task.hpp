#pragma once

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "biovision_tasks/mission_record.hpp"
#include "biovision_tasks/path_follower.hpp"
#include "biovision_tasks/task.hpp"
#include "biovision_tasks/task_parameters.hpp"

namespace biovision_tasks
{
/// Simple macro-task "go to <place|object>", "return home" and micro-task "forward <distance>" (thesis
/// §5.3.3). Excursion mode: plans over the long-term memory (GridPlanner) and hands the base controller
/// one waypoint at a time, replanning every `replan_period` (the LTM changes as the robot drives and new
/// obstacles are seen) and whenever the base reports it is trapped; with no path through the map it drives
/// straight to the goal and lets the base's attractor dynamics find the way. The head looks ahead.
///
/// Objective detection: the goal is in reach. Conclusion: within goal_tolerance (a place) or
/// approach_distance (an object) → Succeeded; the base trapped or faulted for trapped_timeout, no
/// localisation for as long, or an object never found nor remembered → Failed with the reason. Beyond the
/// thesis, "return home" trapped for trapped_timeout first retraces the trail it drove
/// (MissionRecord::wayBack: the planned way may lead past new obstacles the map has not got right) and
/// fails only when trapped as long again.
class GoToTask : public Task
{
public:
  enum class Target
  {
    Place,    ///< (x, y) in map
    Home,     ///< MissionRecord::home
    Object,   ///< where the object was found in this mission, else where the memory has it
    Forward,  ///< `distance` ahead of the pose at the start (micro-task "forward"), no planning
  };
  struct Goal
  {
    Target target = Target::Place;
    double x = 0, y = 0;  ///< Place [m]
    std::string label;    ///< Object
    double distance = 0;  ///< Forward [m], may be negative (backwards is not driven: turns round)
  };

  GoToTask(std::string name, Goal goal, std::shared_ptr<MissionRecord> record, TaskParameters parameters,
           double timeout);

  std::string mode() const override { return goal_.target == Target::Forward ? "" : "excursion"; }
  /// The waypoints of the current plan (map frame), for monitoring.
  const std::vector<cv::Point2d>& waypoints() const { return path_.waypoints(); }

protected:
  void onStart(const Percept& percept) override;
  void onDetect(const Percept& percept) override;
  TaskState onConclude(const Percept& percept) override;
  void onAct(const Percept& percept, MotorCommand& command) override;

private:
  /// Resolves the goal position; false with `why` when it cannot be known (yet).
  bool resolve(const Percept& percept, std::string& why);
  /// Where the base is sent: the place, or an object's approach point facing the robot.
  cv::Point2d aimPoint(const Percept& percept) const;
  /// The trail driven, back from the base to home (MissionRecord::wayBack) and round what the map now
  /// holds on it: its points within robot_radius + squeeze_margin of an obstacle dropped, and a stretch
  /// whose straight line comes that near one (from the base to the first point too) replaced by a
  /// GridPlanner plan within kTrailDetourReach of it (kept straight when there is none, or after
  /// kMaxTrailDetours plans). [m, map]
  std::vector<cv::Point2d> trailBack(const Percept& percept) const;
  static constexpr int kMaxTrailDetours = 16;  ///< plans per trail back (the first stretches matter most)
  /// [m] a detour is planned within the stretch's bounding box grown by this (a crate's detour needs ~1 m)
  static constexpr double kTrailDetourReach = 3.0;

  Goal goal_;
  std::shared_ptr<MissionRecord> record_;
  TaskParameters parameters_;
  bool resolved_ = false;
  cv::Point2d position_;  ///< the resolved goal [m]
  double tolerance_ = 0;  ///< [m]
  PathFollower path_;
  double stuck_since_ = -1;  ///< time the base was first seen trapped/faulted/unlocalised, -1 = not
  double blocked_at_ = -1;   ///< time of the last PathFollower::blockAhead() of this stuck spell
  bool in_reach_ = false;
};
}  // namespace biovision_tasks
