#pragma once

#include <string>

#include "biovision_tasks/motor_command.hpp"
#include "biovision_tasks/percept.hpp"

namespace biovision_tasks
{
enum class TaskState
{
  Pending,  ///< in the buffer, its visuomotor cycle not activated yet
  Running,
  Succeeded,
  Failed,  ///< reason() says why (time-out, trapped, object unknown ...)
  Cancelled,
};

/// "pending", "running", "succeeded", "failed", "cancelled".
const char* toString(TaskState state);
inline bool isFinished(TaskState s)
{
  return s == TaskState::Succeeded || s == TaskState::Failed || s == TaskState::Cancelled;
}

/// A task with the thesis's three blocks (§5.3.3, L1275): a visuomotor action cycle (act), an
/// objective-detection function (detect) and a conclusion-condition function (conclude). Micro-tasks
/// (turn, forward ...) and macro-tasks (MacroTask, search, go to ...) derive from it; a macro-task's blocks
/// are made of its steps' blocks, so the hierarchy is recursive (L1277).
///
/// The TaskManager drives it: start() once when its visuomotor cycle is first activated, then every
/// cycle detect() (also while another task drives) and evaluate(), and act() while it is the active one.
/// Time-outs are enforced here (beyond the thesis, which has none): `timeout` [s] after start(), 0 = none.
class Task
{
public:
  Task(std::string name, double timeout);
  virtual ~Task() = default;
  Task(const Task&) = delete;
  Task& operator=(const Task&) = delete;

  const std::string& name() const { return name_; }
  double timeout() const { return timeout_; }
  TaskState state() const { return state_; }
  const std::string& reason() const { return reason_; }
  double startTime() const { return start_time_; }

  /// Activates the visuomotor cycle (Pending → Running). No effect once started.
  void start(const Percept& percept);
  /// The objective-detection block; evaluated every cycle while the task is buffered and unfinished.
  void detect(const Percept& percept);
  /// The conclusion-condition block, plus the time-out; returns the (new) state. A finished task stays
  /// finished. Pending tasks are not evaluated (returns Pending).
  TaskState evaluate(const Percept& percept);
  /// The visuomotor block: fills `command` (the default command stops the base). Only for Running tasks.
  void act(const Percept& percept, MotorCommand& command);
  /// Finishes the task as Cancelled (no effect once finished).
  void cancel(const std::string& reason);

  /// The micro-task now running ("" for a micro-task itself), its index and count in this macro-task.
  virtual std::string microTask() const { return name_; }
  virtual int step() const { return 0; }
  virtual int steps() const { return 1; }
  /// "exploration" or "excursion" (thesis §5.3.3), "" when neither applies.
  virtual std::string mode() const { return ""; }

protected:
  virtual void onStart(const Percept&) {}
  virtual void onDetect(const Percept&) {}
  /// Running, Succeeded or Failed (with fail()).
  virtual TaskState onConclude(const Percept& percept) = 0;
  virtual void onAct(const Percept& percept, MotorCommand& command) = 0;
  virtual void onCancel(const std::string&) {}
  /// The failure reason when the time-out strikes.
  virtual std::string timeoutReason() const;
  /// Records a failure reason and returns TaskState::Failed, for onConclude.
  TaskState fail(const std::string& reason);

private:
  std::string name_;
  double timeout_;
  TaskState state_ = TaskState::Pending;
  std::string reason_;
  double start_time_ = 0;
};
}  // namespace biovision_tasks
