#include "biovision_tasks/go_to_task.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "biovision_tasks/grid_planner.hpp"

namespace biovision_tasks
{
namespace
{
/// The map around the stretch a-b: its bounding box and `reach` [m] on every side (empty when that misses
/// the map). A detour's A* searches this window, not the whole map: a helper's 2000 x 2000-cell map with
/// ring-shaped obstacles on the trail took 3.6 s for the 16 (failing) plans, inside one task cycle.
OccupancyMap around(const OccupancyMap& map, const cv::Point2d& a, const cv::Point2d& b, double reach)
{
  const cv::Rect w = map.cellsWithin(std::min(a.x, b.x) - reach, std::min(a.y, b.y) - reach, std::max(a.x, b.x) + reach,
                                     std::max(a.y, b.y) + reach);
  if (w.empty())
    return OccupancyMap();
  return OccupancyMap(map.cells()(w).clone(), map.originX() + w.x * map.cellSize(),
                      map.originY() + w.y * map.cellSize(), map.cellSize());
}
}  // namespace

GoToTask::GoToTask(std::string name, Goal goal, std::shared_ptr<MissionRecord> record, TaskParameters parameters,
                   double timeout)
  : Task(std::move(name), timeout),
    goal_(std::move(goal)),
    record_(std::move(record)),
    parameters_(parameters),
    path_(parameters)
{
}

bool GoToTask::resolve(const Percept& percept, std::string& why)
{
  tolerance_ = parameters_.goal_tolerance;
  switch (goal_.target)
  {
    case Target::Place:
      position_ = {goal_.x, goal_.y};
      return true;
    case Target::Home:
      if (!record_->home_known)
      {
        why = "home is not known (no localised pose since the mission began)";
        return false;
      }
      position_ = {record_->home.x, record_->home.y};
      return true;
    case Target::Forward:
      if (!percept.pose_valid)
      {
        why = "no localisation";
        return false;
      }
      position_ = {percept.pose.x + goal_.distance * std::cos(percept.pose.yaw),
                   percept.pose.y + goal_.distance * std::sin(percept.pose.yaw)};
      return true;
    case Target::Object:
    {
      tolerance_ = parameters_.approach_distance;
      const auto f = record_->found.find(goal_.label);
      if (f != record_->found.end())
      {
        position_ = {f->second.x, f->second.y};
        return true;
      }
      const Percept::Object* best = nullptr;
      for (const auto& o : percept.remembered)
        if (o.label == goal_.label && (!best || o.confidence > best->confidence))
          best = &o;
      if (best)
      {
        position_ = {best->x, best->y};
        return true;
      }
      why = "object '" + goal_.label + "' was neither found in this mission nor is it in memory";
      return false;
    }
  }
  return false;
}

void GoToTask::onStart(const Percept& percept)
{
  std::string why;
  resolved_ = resolve(percept, why);
  stuck_since_ = -1;
  if (resolved_)
    path_.setGoal(aimPoint(percept), goal_.target != Target::Forward);
}

cv::Point2d GoToTask::aimPoint(const Percept& percept) const
{
  const cv::Point2d away(percept.pose.x - position_.x, percept.pose.y - position_.y);
  const double n = std::hypot(away.x, away.y);
  if (goal_.target != Target::Object || n < 1e-6)
    return position_;
  return position_ + away * (parameters_.approach_distance * 0.8 / n);
}

void GoToTask::onDetect(const Percept& percept)
{
  if (state() != TaskState::Running || !resolved_ || !percept.pose_valid)
    return;
  in_reach_ = std::hypot(percept.pose.x - position_.x, percept.pose.y - position_.y) <= tolerance_;
}

TaskState GoToTask::onConclude(const Percept& percept)
{
  if (!resolved_)
  {
    std::string why;
    resolved_ = resolve(percept, why);
    if (!resolved_)
      return fail(why);
    path_.setGoal(aimPoint(percept), goal_.target != Target::Forward);
  }
  if (in_reach_)
    return TaskState::Succeeded;
  const bool stuck = !percept.pose_valid || percept.base_trapped || percept.base_fault;
  if (!stuck)
    stuck_since_ = -1;
  else if (stuck_since_ < 0)
    stuck_since_ = percept.time;
  else if (percept.time - stuck_since_ > parameters_.trapped_timeout)
  {
    // The follower's fixed route is the trail back: retraced once.
    if (goal_.target == Target::Home && !path_.followingRoute() && percept.pose_valid && !percept.base_fault)
    {
      const auto route = trailBack(percept);
      if (route.size() >= 2)
      {
        path_.followRoute(route);
        stuck_since_ = -1;
        return TaskState::Running;
      }
    }
    std::ostringstream why;
    if (!percept.pose_valid)
      why << "no localisation for " << parameters_.trapped_timeout << " s";
    else
      why << "the base is " << (percept.base_fault ? "stopped by a fault" : "trapped") << " for "
          << parameters_.trapped_timeout << " s" << (path_.followingRoute() ? " on the trail back" : "");
    return fail(why.str());
  }
  return TaskState::Running;
}

std::vector<cv::Point2d> GoToTask::trailBack(const Percept& percept) const
{
  const cv::Point2d here(percept.pose.x, percept.pose.y);
  std::vector<cv::Point2d> trail = record_->wayBack(here);
  if (percept.map.empty() || trail.size() <= 2)
    return trail;
  // Not through what the map now holds on the trail (the new obstacle of the experiment): no trail point
  // within the base's corridor (robot_radius + squeeze_margin, as its attractor dynamics keep) of it, and
  // a stretch whose straight line comes that near is bridged by a plan round it. make demo's base, trapped beside the new crate, was sent
  // to a trail point inside it, then (those dropped) straight past its corner, and trapped again.
  const cv::Mat1b near = percept.map.inflatedObstacles(parameters_.occupied_threshold,
                                                       parameters_.robot_radius + parameters_.squeeze_margin);
  trail.erase(std::remove_if(trail.begin(), trail.end() - 1,
                             [&](const cv::Point2d& q) {
                               int r, c;
                               return percept.map.cellOf(q.x, q.y, r, c) && near(r, c);
                             }),
              trail.end() - 1);
  const GridPlanner::Options options = GridPlanner::optionsFor(parameters_);
  std::vector<cv::Point2d> route;
  cv::Point2d from = here;
  int plans = 0;  // inside one task cycle: bounded in number and in area (around)
  for (const cv::Point2d& to : trail)
  {
    if (plans < kMaxTrailDetours && !GridPlanner::lineOfSight(percept.map, near, from, to))
    {
      ++plans;
      const OccupancyMap window = around(percept.map, from, to, kTrailDetourReach);
      const auto detour = window.empty() ? std::vector<cv::Point2d>() : GridPlanner::plan(window, from, to, options);
      if (!detour.empty())
        route.insert(route.end(), detour.begin(), detour.end() - 1);  // `to` follows
    }
    route.push_back(to);
    from = to;
  }
  return route;
}

void GoToTask::onAct(const Percept& percept, MotorCommand& command)
{
  command.head_mode = "look_ahead";
  command.mode = mode();
  if (!resolved_ || !percept.pose_valid)
  {
    command.base = MotorCommand::Base::Stop;
    return;
  }
  // Trapped: a fresh plan round what stops it, and another every replan_period while it still does (the
  // first detour may lead into the same obstacle, one the LTM has not got yet).
  if (percept.base_trapped && (stuck_since_ == percept.time || percept.time - blocked_at_ >= parameters_.replan_period))
  {
    path_.blockAhead(percept);
    blocked_at_ = percept.time;
  }
  const cv::Point2d w = path_.waypoint(percept);
  command.base = MotorCommand::Base::Goal;
  command.goal_x = w.x;
  command.goal_y = w.y;
}
}  // namespace biovision_tasks
