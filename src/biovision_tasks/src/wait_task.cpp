#include "biovision_tasks/wait_task.hpp"

namespace biovision_tasks
{
WaitTask::WaitTask(std::string name, double duration, std::string head_mode)
  : Task(std::move(name), 0.0), duration_(duration), head_mode_(std::move(head_mode))
{
}

TaskState WaitTask::onConclude(const Percept& percept)
{
  return percept.time - startTime() >= duration_ ? TaskState::Succeeded : TaskState::Running;
}

void WaitTask::onAct(const Percept&, MotorCommand& command)
{
  command.base = MotorCommand::Base::Stop;
  command.head_mode = head_mode_;
}
}  // namespace biovision_tasks
