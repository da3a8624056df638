#include "biovision_tasks/turn_task.hpp"

#include <cmath>

namespace biovision_tasks
{
TurnTask::TurnTask(double angle, double tolerance, double timeout)
  : Task("turn", timeout), angle_(angle), tolerance_(tolerance)
{
}

void TurnTask::onStart(const Percept& percept)
{
  target_ = std::remainder(percept.pose.yaw + angle_, 2 * M_PI);
}

TaskState TurnTask::onConclude(const Percept& percept)
{
  if (!percept.pose_valid)
    return TaskState::Running;
  return std::abs(std::remainder(percept.pose.yaw - target_, 2 * M_PI)) <= tolerance_ ? TaskState::Succeeded
                                                                                      : TaskState::Running;
}

void TurnTask::onAct(const Percept&, MotorCommand& command)
{
  command.base = MotorCommand::Base::Heading;
  command.heading = target_;
  command.head_mode = "look_ahead";
}
}  // namespace biovision_tasks
