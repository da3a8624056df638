#include "biovision_tasks/path_follower.hpp"

#include <cmath>

#include "biovision_tasks/grid_planner.hpp"

namespace biovision_tasks
{
PathFollower::PathFollower(const TaskParameters& parameters) : parameters_(parameters)
{
}

void PathFollower::setGoal(const cv::Point2d& goal, bool plan)
{
  goal_ = goal;
  plan_ = plan;
  waypoints_.clear();
  replanSoon();
}

cv::Point2d PathFollower::waypoint(const Percept& percept)
{
  if (waypoints_.empty() || percept.time - planned_at_ >= parameters_.replan_period)
  {
    planned_at_ = percept.time;
    waypoints_.clear();
    blocked_.release();
    if (plan_ && !percept.map.empty())
    {
      GridPlanner::Options o;
      o.occupied_threshold = parameters_.occupied_threshold;
      o.radius = parameters_.robot_radius + parameters_.inflation_margin;
      waypoints_ = GridPlanner::plan(percept.map, {percept.pose.x, percept.pose.y}, goal_, o);
      blocked_ = percept.map.inflatedObstacles(o.occupied_threshold, o.radius);
    }
    if (waypoints_.empty())
      waypoints_.push_back(goal_);
  }
  const cv::Point2d here(percept.pose.x, percept.pose.y);
  while (waypoints_.size() > 1 &&
         std::hypot(here.x - waypoints_.front().x, here.y - waypoints_.front().y) <= parameters_.waypoint_tolerance &&
         (blocked_.empty() || GridPlanner::lineOfSight(percept.map, blocked_, here, waypoints_[1])))
    waypoints_.erase(waypoints_.begin());
  return waypoints_.front();
}
}  // namespace biovision_tasks
