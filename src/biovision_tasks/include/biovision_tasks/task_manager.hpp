#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "biovision_tasks/mission_record.hpp"
#include "biovision_tasks/motor_command.hpp"
#include "biovision_tasks/percept.hpp"
#include "biovision_tasks/task.hpp"
#include "biovision_tasks/task_parameters.hpp"
#include "biovision_tasks/task_spec.hpp"

namespace biovision_tasks
{
/// The central agent of thesis §5.3.3 (L1273–1279): a task buffer of top-level tasks and the three block
/// buffers. Every cycle (step()):
///  1. the objective-detection buffer: detect() of every buffered task, also those waiting their turn;
///  2. the conclusion-condition buffer: evaluate() of every started task (the active one and concurrent
///     ones) — time-outs included; a finished task leaves all buffers, and its failure policy applies
///     (on_failure: continue, abort the rest, or run a fallback task instead of the rest);
///  3. the visuomotor buffer: only its head — the highest priority, then the oldest — acts; it is started
///     when it first gets there, in the same cycle, so the robot never idles between tasks.
/// With no task, or no localisation, the command stops the base. A progress monitor (beyond the thesis):
/// a base that was told to drive but has not moved stall_distance in stall_time counts as trapped for the
/// tasks, whatever the base controller says. ROS-free; not thread-safe (one caller).
class TaskManager
{
public:
  struct Status
  {
    std::string macro_task, micro_task, mode, message;
    int step = 0, steps = 0;
    TaskState state = TaskState::Pending;  ///< Pending = idle (no task ever ran)
  };
  struct Finished
  {
    int id;
    std::string name;
    TaskState state;
    std::string reason;
    double start, end;  ///< [s]
  };

  explicit TaskManager(const TaskParameters& parameters = TaskParameters());

  /// Builds a task from its spec (validate()d; throws std::invalid_argument) and buffers it; returns its id.
  int add(const TaskSpec& spec);
  /// Builds without buffering (for tests and composite tasks). Throws std::invalid_argument.
  std::unique_ptr<Task> build(const TaskSpec& spec) const;
  /// One cycle; percept.time must not decrease (call reset() when the clock jumps back).
  MotorCommand step(const Percept& percept);
  /// Cancels one buffered task (false when there is none with this id) or all of them.
  bool cancel(int id, const std::string& reason);
  void cancelAll(const std::string& reason);
  /// Forgets everything: buffered tasks (cancelled), the mission record (home, found objects), history.
  void reset();

  bool idle() const { return buffer_.empty(); }
  Status status() const;
  /// Finished top-level tasks in the order they finished.
  const std::vector<Finished>& finished() const { return finished_; }
  const MissionRecord& record() const { return *record_; }
  /// The task now driving the robot, nullptr when idle.
  const Task* activeTask() const;

private:
  struct Entry
  {
    int id;
    std::unique_ptr<Task> task;
    TaskSpec spec;
    long order;
  };
  void finish(size_t index, double time);
  /// Moves the buffer's finished tasks to finished_.
  void dropFinished(double time);
  /// After a successful greet: an action that is a task without arguments (stop, wait, look_ahead,
  /// look_around, return_home) cancels the plan and runs instead; others let it go on (noted in the
  /// greet's Finished reason).
  void runGestureAction(const std::string& action, int priority, double time);
  /// An LTM obstacle within greet_distance and kGreetCone in front of the robot.
  bool obstacleInFront(const Percept& percept) const;
  bool greetBuffered() const;
  void sortVisuomotor();

  TaskParameters parameters_;
  std::shared_ptr<MissionRecord> record_;
  std::vector<Entry> buffer_;  ///< the task buffer; its order is the visuomotor buffer's
  std::vector<Finished> finished_;
  int next_id_ = 1;
  long next_order_ = 0;
  bool have_last_pose_ = false;
  Percept::Pose last_pose_;
  bool driving_ = false;         ///< the last command drove the base
  Percept::Pose progress_pose_;  ///< where the robot was when it last made progress
  double progress_time_ = 0;     ///< [s] and when
  double last_time_ = 0;
  double greet_ready_time_ = -std::numeric_limits<double>::infinity();  ///< [s] obstacles may start a greet from then
};
}  // namespace biovision_tasks
