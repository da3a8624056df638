#pragma once

#include "biovision_tasks/task.hpp"

namespace biovision_tasks
{
/// Micro-tasks that keep the base still for `duration` [s] with the head in `head_mode`: "stop"
/// (duration 0, head unchanged), "wait", "look_ahead" (head look_ahead), "look_around" (head explore).
/// Succeeds when the duration has passed.
class WaitTask : public Task
{
public:
  WaitTask(std::string name, double duration, std::string head_mode);

protected:
  TaskState onConclude(const Percept& percept) override;
  void onAct(const Percept& percept, MotorCommand& command) override;

private:
  double duration_;
  std::string head_mode_;
};
}  // namespace biovision_tasks
