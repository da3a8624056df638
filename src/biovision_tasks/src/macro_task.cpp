#include "biovision_tasks/macro_task.hpp"

#include <stdexcept>

namespace biovision_tasks
{
MacroTask::MacroTask(std::string name, double timeout) : Task(std::move(name), timeout)
{
}

void MacroTask::addStep(std::unique_ptr<Task> step, bool optional)
{
  if (state() != TaskState::Pending)
    throw std::logic_error("MacroTask " + name() + ": steps are added before it starts");
  if (!step)
    throw std::invalid_argument("MacroTask " + name() + ": null step");
  steps_.push_back({std::move(step), optional});
}

std::string MacroTask::microTask() const
{
  return current_ < steps_.size() ? steps_[current_].task->microTask() : "";
}

std::string MacroTask::mode() const
{
  return current_ < steps_.size() ? steps_[current_].task->mode() : "";
}

void MacroTask::onStart(const Percept& percept)
{
  current_ = 0;
  if (!steps_.empty())
    steps_[0].task->start(percept);
}

void MacroTask::onDetect(const Percept& percept)
{
  for (size_t i = current_; i < steps_.size(); ++i)
    steps_[i].task->detect(percept);
}

TaskState MacroTask::onConclude(const Percept& percept)
{
  while (current_ < steps_.size())
  {
    Step& s = steps_[current_];
    const TaskState st = s.task->evaluate(percept);
    if (st == TaskState::Running)
      return TaskState::Running;
    if ((st == TaskState::Failed || st == TaskState::Cancelled) && !s.optional)
      return fail("step " + std::to_string(current_ + 1) + "/" + std::to_string(steps_.size()) + " (" + s.task->name() +
                  "): " + s.task->reason());
    // Succeeded, or an optional step failed: the next step's visuomotor cycle takes over at once.
    if (++current_ < steps_.size())
      steps_[current_].task->start(percept);
  }
  return TaskState::Succeeded;
}

void MacroTask::onAct(const Percept& percept, MotorCommand& command)
{
  if (current_ < steps_.size())
    steps_[current_].task->act(percept, command);
}

void MacroTask::onCancel(const std::string& reason)
{
  for (size_t i = current_; i < steps_.size(); ++i)
    steps_[i].task->cancel(reason);
}
}  // namespace biovision_tasks
