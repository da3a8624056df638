#include "biovision_tasks/greet_task.hpp"

#include <sstream>
#include <utility>

namespace biovision_tasks
{
GreetTask::GreetTask(std::string name, double timeout) : Task(std::move(name), timeout)
{
}

TaskState GreetTask::onConclude(const Percept& percept)
{
  // An action published before the task started belongs to an earlier greeting.
  if (percept.gesture_action.empty() || percept.gesture_action_time < startTime())
    return TaskState::Running;
  action_ = percept.gesture_action;
  return TaskState::Succeeded;
}

void GreetTask::onAct(const Percept&, MotorCommand& command)
{
  command.base = MotorCommand::Base::Stop;
  command.greet = true;  // the head is the HRI behaviour's meanwhile: no head mode
}

std::string GreetTask::timeoutReason() const
{
  std::ostringstream s;
  s << "no gesture read in " << timeout() << " s (nobody there, no face found or no known gesture)";
  return s.str();
}
}  // namespace biovision_tasks
