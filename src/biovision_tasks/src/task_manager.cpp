#include "biovision_tasks/task_manager.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "biovision_tasks/go_to_task.hpp"
#include "biovision_tasks/macro_task.hpp"
#include "biovision_tasks/search_task.hpp"
#include "biovision_tasks/turn_task.hpp"
#include "biovision_tasks/wait_task.hpp"

namespace biovision_tasks
{
TaskManager::TaskManager(const TaskParameters& parameters)
  : parameters_(parameters), record_(std::make_shared<MissionRecord>())
{
  parameters_.validate();
}

std::unique_ptr<Task> TaskManager::build(const TaskSpec& spec) const
{
  spec.validate();
  const auto timeout = [&spec](double fallback) { return spec.timeout >= 0 ? spec.timeout : fallback; };
  const std::string& t = spec.type;
  if (t == "wait" || t == "stop")
    return std::make_unique<WaitTask>(t, spec.duration, "");
  if (t == "look_ahead")
    return std::make_unique<WaitTask>(t, spec.duration, "look_ahead");
  if (t == "look_around")
    return std::make_unique<WaitTask>(t, spec.duration, "explore");
  if (t == "turn")
    return std::make_unique<TurnTask>(spec.angle, 0.1, timeout(60.0));
  if (t == "search" || t == "explore")
    return std::make_unique<SearchTask>(spec.object, spec.duration, record_, parameters_,
                                        timeout(t == "search" ? parameters_.search_timeout : 0.0));
  if (t == "go_to" || t == "return_home" || t == "forward")
  {
    GoToTask::Goal g;
    if (t == "return_home")
      g.target = GoToTask::Target::Home;
    else if (t == "forward")
    {
      g.target = GoToTask::Target::Forward;
      g.distance = spec.distance;
    }
    else if (!spec.object.empty())
    {
      g.target = GoToTask::Target::Object;
      g.label = spec.object;
    }
    else
    {
      g.x = spec.x;
      g.y = spec.y;
    }
    return std::make_unique<GoToTask>(spec.displayName(), g, record_, parameters_, timeout(parameters_.go_to_timeout));
  }
  // sequence
  auto macro = std::make_unique<MacroTask>(spec.displayName(), timeout(0.0));
  for (const auto& s : spec.steps)
    macro->addStep(build(s), s.optional);
  return macro;
}

int TaskManager::add(const TaskSpec& spec)
{
  auto task = build(spec);
  const int id = next_id_++;
  buffer_.push_back({id, std::move(task), spec, next_order_++});
  sortVisuomotor();
  return id;
}

void TaskManager::sortVisuomotor()
{
  std::stable_sort(buffer_.begin(), buffer_.end(), [](const Entry& a, const Entry& b) {
    return a.spec.priority != b.spec.priority ? a.spec.priority > b.spec.priority : a.order < b.order;
  });
}

const Task* TaskManager::activeTask() const
{
  return buffer_.empty() ? nullptr : buffer_.front().task.get();
}

void TaskManager::finish(size_t index, double time)
{
  Entry e = std::move(buffer_[index]);
  buffer_.erase(buffer_.begin() + static_cast<long>(index));
  finished_.push_back({e.id, e.task->name(), e.task->state(), e.task->reason(), e.task->startTime(), time});
  if (e.task->state() != TaskState::Failed || e.spec.on_failure == "continue")
    return;
  const std::string why = "'" + e.task->name() + "' failed: " + e.task->reason();
  cancelAll("cancelled because " + why);
  // The fallback replaces the rest of the plan (e.g. search failed → return home).
  for (size_t i = 0; i < buffer_.size();)
    if (isFinished(buffer_[i].task->state()))
    {
      Entry c = std::move(buffer_[i]);
      buffer_.erase(buffer_.begin() + static_cast<long>(i));
      finished_.push_back({c.id, c.task->name(), c.task->state(), c.task->reason(), c.task->startTime(), time});
    }
    else
      ++i;
  if (e.spec.on_failure != "abort")
  {
    TaskSpec fallback;
    fallback.type = e.spec.on_failure;
    if (fallback.type == "search" || fallback.type == "go_to")
      fallback.object = e.spec.object;
    fallback.priority = e.spec.priority;
    try
    {
      add(fallback);
    }
    catch (const std::invalid_argument&)
    {
      // e.g. on_failure: go_to without a place: nothing to fall back to; the rest is already cancelled.
    }
  }
}

MotorCommand TaskManager::step(const Percept& input)
{
  Percept percept = input;
  // Progress monitor: moved stall_distance since the last progress, or not driving: progress now.
  if (!driving_ || !percept.pose_valid ||
      std::hypot(percept.pose.x - progress_pose_.x, percept.pose.y - progress_pose_.y) >= parameters_.stall_distance)
  {
    progress_pose_ = percept.pose;
    progress_time_ = percept.time;
  }
  if (percept.time - progress_time_ > parameters_.stall_time)
    percept.base_trapped = true;
  if (percept.pose_valid)
  {
    if (!record_->home_known)
    {
      record_->home_known = true;
      record_->home = percept.pose;
    }
    if (have_last_pose_)
      record_->path_length += std::hypot(percept.pose.x - last_pose_.x, percept.pose.y - last_pose_.y);
    record_->extendTrail(percept.pose.x, percept.pose.y);
    last_pose_ = percept.pose;
    have_last_pose_ = true;
  }
  last_time_ = percept.time;

  // Concurrent tasks run their detection and conclusion from the start; the visuomotor head is started.
  for (auto& e : buffer_)
    if (e.spec.concurrent)
      e.task->start(percept);
  if (!buffer_.empty())
    buffer_.front().task->start(percept);

  // 1. Objective-detection buffer.
  for (auto& e : buffer_)
    e.task->detect(percept);
  // 2. Conclusion-condition buffer; finishing may start the next visuomotor cycle, evaluated this cycle too.
  for (bool changed = true; changed;)
  {
    changed = false;
    for (size_t i = 0; i < buffer_.size(); ++i)
    {
      Task& t = *buffer_[i].task;
      if (t.state() == TaskState::Pending)
        continue;
      if (isFinished(t.evaluate(percept)))
      {
        finish(i, percept.time);
        if (!buffer_.empty())
          buffer_.front().task->start(percept);
        changed = true;
        break;
      }
    }
  }
  // 3. Visuomotor buffer: its head acts.
  MotorCommand command;
  if (!buffer_.empty())
    buffer_.front().task->act(percept, command);
  if (!percept.pose_valid)
    command.base = MotorCommand::Base::Stop;
  driving_ = command.base != MotorCommand::Base::Stop;
  return command;
}

bool TaskManager::cancel(int id, const std::string& reason)
{
  for (size_t i = 0; i < buffer_.size(); ++i)
    if (buffer_[i].id == id)
    {
      buffer_[i].task->cancel(reason);
      finish(i, last_time_);
      return true;
    }
  return false;
}

void TaskManager::cancelAll(const std::string& reason)
{
  for (auto& e : buffer_)
    e.task->cancel(reason);
}

void TaskManager::reset()
{
  cancelAll("reset");
  buffer_.clear();
  finished_.clear();
  *record_ = MissionRecord();
  have_last_pose_ = false;
  driving_ = false;
}

TaskManager::Status TaskManager::status() const
{
  Status s;
  if (const Task* t = activeTask())
  {
    s.macro_task = t->name();
    s.micro_task = t->microTask();
    s.step = t->step();
    s.steps = t->steps();
    s.mode = t->mode();
    s.state = TaskState::Running;
    s.message = std::to_string(buffer_.size()) + " task(s) buffered";
    return s;
  }
  if (!finished_.empty())
  {
    const Finished& f = finished_.back();
    s.macro_task = f.name;
    s.state = f.state;
    s.message = f.reason.empty() ? std::string(toString(f.state)) : f.reason;
  }
  return s;
}
}  // namespace biovision_tasks
