#include "biovision_tasks/task_manager.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "biovision_tasks/go_to_task.hpp"
#include "biovision_tasks/greet_task.hpp"
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
  if (t == "greet")
    return std::make_unique<GreetTask>(spec.displayName(), timeout(parameters_.greet_timeout));
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
  if (const auto* greet = dynamic_cast<const GreetTask*>(e.task.get()))
  {
    greet_ready_time_ = time + parameters_.greet_cooldown;
    if (greet->state() == TaskState::Succeeded)
      runGestureAction(greet->action(), e.spec.priority, time);
  }
  if (e.task->state() != TaskState::Failed || e.spec.on_failure == "continue")
    return;
  const std::string why = "'" + e.task->name() + "' failed: " + e.task->reason();
  cancelAll("cancelled because " + why);
  // The fallback replaces the rest of the plan (e.g. search failed → return home).
  dropFinished(time);
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

void TaskManager::dropFinished(double time)
{
  for (size_t i = 0; i < buffer_.size();)
    if (isFinished(buffer_[i].task->state()))
    {
      Entry c = std::move(buffer_[i]);
      buffer_.erase(buffer_.begin() + static_cast<long>(i));
      finished_.push_back({c.id, c.task->name(), c.task->state(), c.task->reason(), c.task->startTime(), time});
    }
    else
      ++i;
}

void TaskManager::runGestureAction(const std::string& action, int priority, double time)
{
  // Actions that are tasks without arguments replace the plan; "continue" and anything else (e.g.
  // biovision_hri's "follow", which needs a person tracker) let the interrupted tasks go on.
  static const std::set<std::string> kReplacing = {"stop", "wait", "look_ahead", "look_around", "return_home"};
  std::string& note = finished_.back().reason;  // the greet's entry (set before dropFinished() adds more)
  if (!kReplacing.count(action))
  {
    note = "gesture action '" + action + "'" + (action == "continue" ? std::string() : " is no task the manager runs") +
           ": the interrupted tasks go on";
    return;
  }
  note = "gesture action '" + action + "' replaces the plan";
  cancelAll("replaced by the gesture action '" + action + "'");
  dropFinished(time);
  TaskSpec s;
  s.type = action;
  s.priority = priority;
  add(s);
}

bool TaskManager::obstacleInFront(const Percept& p) const
{
  const OccupancyMap& m = p.map;
  const double r = parameters_.greet_distance;
  if (m.empty() || r <= 0)
    return false;
  const cv::Rect box = m.cellsWithin(p.pose.x - r, p.pose.y - r, p.pose.x + r, p.pose.y + r);
  for (int row = box.y; row < box.br().y; ++row)
    for (int col = box.x; col < box.br().x; ++col)
    {
      const unsigned char v = m.cells()(row, col);
      if (v == OccupancyMap::kUnknown || v < parameters_.occupied_threshold)
        continue;
      const cv::Point2d c = m.centreOf(row, col);
      const double dx = c.x - p.pose.x, dy = c.y - p.pose.y;
      const double bearing = std::remainder(std::atan2(dy, dx) - p.pose.yaw, 2 * M_PI);
      if (std::hypot(dx, dy) <= r && std::abs(bearing) <= TaskParameters::kGreetCone)
        return true;
    }
  return false;
}

bool TaskManager::greetBuffered() const
{
  return std::any_of(buffer_.begin(), buffer_.end(),
                     [](const Entry& e) { return dynamic_cast<const GreetTask*>(e.task.get()) != nullptr; });
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

  // Thesis §2.1: an obstacle in front while driving may be a person: greet it above the active task.
  if (driving_ && percept.pose_valid && !buffer_.empty() && percept.time >= greet_ready_time_ && !greetBuffered() &&
      obstacleInFront(percept))
  {
    TaskSpec greet;
    greet.type = "greet";
    greet.name = "greet (obstacle in front)";
    greet.priority = buffer_.front().spec.priority + 1;
    add(greet);
  }

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
  greet_ready_time_ = -std::numeric_limits<double>::infinity();
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
