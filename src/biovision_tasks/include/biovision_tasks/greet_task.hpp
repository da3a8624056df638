#pragma once

#include <string>

#include "biovision_tasks/task.hpp"

namespace biovision_tasks
{
/// Meets a person (thesis §2.1, L318/L415: the robot looks up at an obstacle in front, finds a face and
/// reads a hand gesture): the base stands still and MotorCommand::greet asks biovision_hri's greet
/// behaviour to do the looking; the task succeeds when that behaviour publishes an action (the gesture's
/// entry in its `actions` table) after the task started, and fails at its time-out otherwise (no person,
/// no face, no known gesture). TaskManager then runs the action (see there).
class GreetTask : public Task
{
public:
  GreetTask(std::string name, double timeout);
  /// The action read ("" until the task succeeded).
  const std::string& action() const { return action_; }

protected:
  TaskState onConclude(const Percept& percept) override;
  void onAct(const Percept& percept, MotorCommand& command) override;
  std::string timeoutReason() const override;

private:
  std::string action_;
};
}  // namespace biovision_tasks
