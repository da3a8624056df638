#include "biovision_tasks/search_task.hpp"

#include <cmath>
#include <sstream>

namespace biovision_tasks
{
SearchTask::SearchTask(std::string label, double duration, std::shared_ptr<MissionRecord> record,
                       TaskParameters parameters, double timeout)
  : Task(label.empty() ? "explore" : "search " + label, timeout),
    label_(std::move(label)),
    duration_(duration),
    record_(std::move(record)),
    parameters_(parameters),
    exploration_(parameters),
    path_(parameters)
{
}

std::string SearchTask::microTask() const
{
  if (excursion_)
    return "go_to " + label_ + " (remembered)";
  return has_goal_ ? "explore" : "look_around";
}

void SearchTask::onStart(const Percept& percept)
{
  // Excursion first when the memory already knows where the object is (the thesis' excursion mode).
  if (label_.empty())
    return;
  for (const auto& o : percept.remembered)
    if (o.label == label_ && o.confidence >= parameters_.min_memory_confidence)
    {
      GoToTask::Goal g;
      g.target = GoToTask::Target::Place;
      g.x = o.x;
      g.y = o.y;
      // Close enough to recognise it: the approach distance.
      TaskParameters p = parameters_;
      p.goal_tolerance = parameters_.approach_distance;
      excursion_ = std::make_unique<GoToTask>("go_to " + label_, g, record_, p, 0.0);
      excursion_->start(percept);
      return;
    }
}

void SearchTask::onDetect(const Percept& percept)
{
  exploration_.recordVisit(percept);
  if (label_.empty() || found_)
    return;
  for (const auto& o : percept.seen)
  {
    if (o.label != label_)
      continue;
    const bool confirms = candidate_ && o.last_seen > candidate_->last_seen &&
                          o.last_seen - candidate_->last_seen <= parameters_.confirm_time &&
                          std::hypot(o.x - candidate_->x, o.y - candidate_->y) <= parameters_.confirm_distance;
    if (parameters_.confirm_distance <= 0 || confirms)
    {
      found_ = true;
      record_->found[label_] = o;
      return;
    }
    // The newest sighting waits for its confirmation (a sighting of the same frame is no second one).
    if (!candidate_ || o.last_seen > candidate_->last_seen)
      candidate_ = o;
  }
}

TaskState SearchTask::onConclude(const Percept& percept)
{
  if (found_)
    return TaskState::Succeeded;
  if (label_.empty() && percept.time - startTime() >= duration_)
    return TaskState::Succeeded;
  if (excursion_)
  {
    excursion_->detect(percept);
    const TaskState s = excursion_->evaluate(percept);
    if (s != TaskState::Running)
      excursion_.reset();  // there and not recognised, or not reachable: explore
  }
  return TaskState::Running;
}

void SearchTask::onAct(const Percept& percept, MotorCommand& command)
{
  command.mode = mode();
  if (excursion_)
  {
    excursion_->act(percept, command);
    command.head_mode = "explore";  // look for it on the way
    command.mode = "excursion";
    return;
  }
  // Stop and look: the head explores while the base stands at a new exploration goal, and looks ahead
  // while it drives (the base's STM then covers where it goes); look_time 0 explores all the time.
  command.head_mode = parameters_.look_time > 0 ? "look_ahead" : "explore";
  if (percept.time < look_until_)
  {
    // Turning in place, a quarter turn ahead of the heading all the time: the view sweeps round.
    command.head_mode = "explore";
    command.base = MotorCommand::Base::Heading;
    command.heading = std::remainder(percept.pose.yaw + M_PI / 2, 2 * M_PI);
    return;
  }
  if (!percept.pose_valid)
  {
    command.base = MotorCommand::Base::Stop;
    return;
  }
  const cv::Point2d here(percept.pose.x, percept.pose.y);
  if (percept.base_trapped || percept.base_fault)
  {
    if (trapped_since_ < 0)
      trapped_since_ = percept.time;
  }
  else
    trapped_since_ = -1;
  const cv::Point2d& goal = path_.goal();
  const bool reached = has_goal_ && std::hypot(goal.x - here.x, goal.y - here.y) <= parameters_.goal_tolerance;
  const bool stale = percept.time - goal_time_ >= parameters_.explore_period;
  const bool trapped = trapped_since_ >= 0 && percept.time - trapped_since_ > 2.0;
  if (trapped && has_goal_)
    exploration_.markUnreachable(goal, percept.time);
  if (!has_goal_ || reached || stale || trapped)
  {
    cv::Point2d next;
    const cv::Point2d home = record_->home_known ? cv::Point2d(record_->home.x, record_->home.y) : here;
    has_goal_ = exploration_.nextGoal(percept, home, next);
    if (has_goal_)
      path_.setGoal(next);
    // The look at the new goal's start does not count against explore_period.
    look_until_ = trapped ? -1.0 : percept.time + parameters_.look_time;
    goal_time_ = std::max(percept.time, look_until_);
    trapped_since_ = -1;
  }
  if (has_goal_)
  {
    const cv::Point2d w = path_.waypoint(percept);
    command.base = MotorCommand::Base::Goal;
    command.goal_x = w.x;
    command.goal_y = w.y;
  }
  else
  {
    // Nowhere free to go: turn round in place, the STM and LTM will tell more from another view.
    command.base = MotorCommand::Base::Heading;
    command.heading = std::remainder(percept.pose.yaw + M_PI / 2, 2 * M_PI);
  }
}

void SearchTask::onCancel(const std::string& reason)
{
  if (excursion_)
    excursion_->cancel(reason);
}
}  // namespace biovision_tasks

namespace biovision_tasks
{
std::string SearchTask::timeoutReason() const
{
  if (label_.empty())
    return Task::timeoutReason();
  std::ostringstream why;
  why << "object '" << label_ << "' never found in " << timeout() << " s";
  return why.str();
}
}  // namespace biovision_tasks
