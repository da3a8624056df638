#pragma once

#include <memory>
#include <optional>
#include <string>

#include "biovision_tasks/exploration_planner.hpp"
#include "biovision_tasks/go_to_task.hpp"
#include "biovision_tasks/mission_record.hpp"
#include "biovision_tasks/path_follower.hpp"
#include "biovision_tasks/task.hpp"
#include "biovision_tasks/task_parameters.hpp"

namespace biovision_tasks
{
/// Simple macro-task "search <object>" (thesis §5.3.3, "search" is one of its pre-programmed macro-tasks)
/// and "explore" (no object, succeeds after `duration`).
///
/// Visuomotor cycle: when the object memory remembers the object (confidence >= min_memory_confidence),
/// an excursion there first (GoToTask); otherwise, or when it is not there, exploration (ExplorationPlanner
/// goals, a new one when reached, trapped or every explore_period): at each new goal the base stands for
/// look_time while the head explores (saliency-driven attractor dynamics, which is what finds objects),
/// then drives there with the head looking ahead (look_time 0: the head explores all the time). Objective detection: the object recognised in the
/// view twice, the second sighting within confirm_distance and confirm_time of the first; its map position is recorded in the MissionRecord (a later "go to <object>" or the memory use it).
/// Conclusion: detected → Succeeded; the time-out (the manager's default: search_timeout) → Failed
/// "object never found".
class SearchTask : public Task
{
public:
  /// label "" = explore for `duration` [s].
  SearchTask(std::string label, double duration, std::shared_ptr<MissionRecord> record, TaskParameters parameters,
             double timeout);

  std::string microTask() const override;
  std::string mode() const override { return excursion_ ? "excursion" : "exploration"; }
  bool found() const { return found_; }

protected:
  void onStart(const Percept& percept) override;
  void onDetect(const Percept& percept) override;
  TaskState onConclude(const Percept& percept) override;
  void onAct(const Percept& percept, MotorCommand& command) override;
  void onCancel(const std::string& reason) override;
  std::string timeoutReason() const override;

private:
  std::string label_;
  double duration_;
  std::shared_ptr<MissionRecord> record_;
  TaskParameters parameters_;
  ExplorationPlanner exploration_;
  std::unique_ptr<GoToTask> excursion_;  ///< to where the memory has the object, while it runs
  bool found_ = false;
  std::optional<Percept::Object> candidate_;  ///< the last unconfirmed sighting of the object
  PathFollower path_;
  bool has_goal_ = false;
  double goal_time_ = -1e9;
  double trapped_since_ = -1;
  double look_until_ = -1;  // [s] the base stands and the head explores until then
};
}  // namespace biovision_tasks
