#pragma once

#include <memory>
#include <vector>

#include "biovision_tasks/task.hpp"

namespace biovision_tasks
{
/// A macro-task: a sequence of steps (micro-tasks or macro-tasks, so the hierarchy is recursive, thesis
/// §5.3.3 L1277). Its visuomotor block is its current step's; its detection block runs every unfinished
/// step's detection (evidence found early counts later); its conclusion follows the current step: a
/// succeeded step starts the next, the last one's success is the macro-task's, a failed step fails it with
/// "step k/n (name): reason" unless the step is optional (then the sequence goes on).
class MacroTask : public Task
{
public:
  MacroTask(std::string name, double timeout);

  /// Appends a step; `optional`: its failure does not fail the macro-task. Only before start().
  void addStep(std::unique_ptr<Task> step, bool optional = false);

  std::string microTask() const override;
  int step() const override { return static_cast<int>(current_); }
  int steps() const override { return static_cast<int>(steps_.size()); }
  std::string mode() const override;
  const Task& stepAt(int i) const { return *steps_.at(i).task; }

protected:
  void onStart(const Percept& percept) override;
  void onDetect(const Percept& percept) override;
  TaskState onConclude(const Percept& percept) override;
  void onAct(const Percept& percept, MotorCommand& command) override;
  void onCancel(const std::string& reason) override;

private:
  struct Step
  {
    std::unique_ptr<Task> task;
    bool optional;
  };
  std::vector<Step> steps_;
  size_t current_ = 0;
};
}  // namespace biovision_tasks
