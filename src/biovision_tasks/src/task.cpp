#include "biovision_tasks/task.hpp"

#include <cmath>
#include <sstream>

namespace biovision_tasks
{
const char* toString(TaskState state)
{
  switch (state)
  {
    case TaskState::Pending:
      return "pending";
    case TaskState::Running:
      return "running";
    case TaskState::Succeeded:
      return "succeeded";
    case TaskState::Failed:
      return "failed";
    case TaskState::Cancelled:
      return "cancelled";
  }
  return "?";
}

Task::Task(std::string name, double timeout) : name_(std::move(name)), timeout_(timeout)
{
}

void Task::start(const Percept& percept)
{
  if (state_ != TaskState::Pending)
    return;
  state_ = TaskState::Running;
  start_time_ = percept.time;
  onStart(percept);
}

void Task::detect(const Percept& percept)
{
  if (!isFinished(state_))
    onDetect(percept);
}

TaskState Task::evaluate(const Percept& percept)
{
  if (state_ != TaskState::Running)
    return state_;
  const TaskState s = onConclude(percept);
  if (s == TaskState::Running && timeout_ > 0 && percept.time - start_time_ > timeout_)
  {
    fail(timeoutReason());
    onCancel(reason_);  // lets a macro-task finish its running step
    return state_;
  }
  if (s == TaskState::Succeeded || s == TaskState::Failed)
    state_ = s;
  return state_;
}

void Task::act(const Percept& percept, MotorCommand& command)
{
  if (state_ == TaskState::Running)
    onAct(percept, command);
}

void Task::cancel(const std::string& reason)
{
  if (isFinished(state_))
    return;
  state_ = TaskState::Cancelled;
  reason_ = reason;
  onCancel(reason);
}

std::string Task::timeoutReason() const
{
  std::ostringstream why;
  why << "time-out after " << timeout_ << " s";
  return why.str();
}

TaskState Task::fail(const std::string& reason)
{
  state_ = TaskState::Failed;
  reason_ = reason;
  return TaskState::Failed;
}
}  // namespace biovision_tasks
