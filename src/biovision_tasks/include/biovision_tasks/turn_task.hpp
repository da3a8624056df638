#pragma once

#include "biovision_tasks/task.hpp"

namespace biovision_tasks
{
/// Micro-task "turn": turns the base in place by `angle` [rad, + = left] from its heading at the start.
/// Succeeds within `tolerance` [rad]; the head looks ahead.
class TurnTask : public Task
{
public:
  TurnTask(double angle, double tolerance, double timeout);

protected:
  void onStart(const Percept& percept) override;
  TaskState onConclude(const Percept& percept) override;
  void onAct(const Percept& percept, MotorCommand& command) override;

private:
  double angle_, tolerance_, target_ = 0;
};
}  // namespace biovision_tasks
