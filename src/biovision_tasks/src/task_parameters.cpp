#include "biovision_tasks/task_parameters.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace biovision_tasks
{
namespace
{
void check(const char* name, double v, double lo, double hi)
{
  if (!(v >= lo && v <= hi) || !std::isfinite(v))
  {
    std::ostringstream s;
    s << "TaskParameters: " << name << " " << v << " outside [" << lo << ", " << hi << "]";
    throw std::invalid_argument(s.str());
  }
}
}  // namespace

void TaskParameters::validate() const
{
  check("goal_tolerance", goal_tolerance, 0.05, 5.0);
  check("approach_distance", approach_distance, 0.3, 5.0);
  check("waypoint_tolerance", waypoint_tolerance, 0.05, 5.0);
  check("robot_radius", robot_radius, 0.05, 2.0);
  check("inflation_margin", inflation_margin, 0.0, 2.0);
  check("squeeze_margin", squeeze_margin, 0.0, 2.0);
  check("occupied_threshold", occupied_threshold, 1, 100);
  check("replan_period", replan_period, 0.1, 600.0);
  check("explore_step", explore_step, 0.2, 20.0);
  check("explore_period", explore_period, 1.0, 600.0);
  check("look_time", look_time, 0.0, 600.0);
  check("visit_cell", visit_cell, 0.05, 5.0);
  check("view_range", view_range, 0.0, 20.0);
  check("view_angle", view_angle, 0.01, 6.3);
  check("frontier_retry_time", frontier_retry_time, 1.0, 36000.0);
  check("home_range_cost", home_range_cost, 0.0, 100.0);
  check("trapped_timeout", trapped_timeout, 1.0, 3600.0);
  check("stall_time", stall_time, 1.0, 3600.0);
  check("stall_distance", stall_distance, 0.01, 10.0);
  check("min_memory_confidence", min_memory_confidence, 0.0, 1.0);
  check("confirm_distance", confirm_distance, 0.0, 10.0);
  check("confirm_time", confirm_time, 0.1, 60.0);
  check("search_timeout", search_timeout, 1.0, 36000.0);
  check("go_to_timeout", go_to_timeout, 1.0, 36000.0);
  check("greet_timeout", greet_timeout, 1.0, 600.0);
  check("greet_distance", greet_distance, 0.0, 5.0);
  check("greet_cooldown", greet_cooldown, 0.0, 3600.0);
}

const std::vector<std::pair<std::string, double TaskParameters::*>>& TaskParameters::namedDoubles()
{
  static const std::vector<std::pair<std::string, double TaskParameters::*>> fields = {
      {"goal_tolerance", &TaskParameters::goal_tolerance},
      {"approach_distance", &TaskParameters::approach_distance},
      {"waypoint_tolerance", &TaskParameters::waypoint_tolerance},
      {"robot_radius", &TaskParameters::robot_radius},
      {"inflation_margin", &TaskParameters::inflation_margin},
      {"squeeze_margin", &TaskParameters::squeeze_margin},
      {"replan_period", &TaskParameters::replan_period},
      {"explore_step", &TaskParameters::explore_step},
      {"explore_period", &TaskParameters::explore_period},
      {"look_time", &TaskParameters::look_time},
      {"visit_cell", &TaskParameters::visit_cell},
      {"view_range", &TaskParameters::view_range},
      {"view_angle", &TaskParameters::view_angle},
      {"frontier_retry_time", &TaskParameters::frontier_retry_time},
      {"home_range_cost", &TaskParameters::home_range_cost},
      {"trapped_timeout", &TaskParameters::trapped_timeout},
      {"stall_time", &TaskParameters::stall_time},
      {"stall_distance", &TaskParameters::stall_distance},
      {"min_memory_confidence", &TaskParameters::min_memory_confidence},
      {"confirm_distance", &TaskParameters::confirm_distance},
      {"confirm_time", &TaskParameters::confirm_time},
      {"search_timeout", &TaskParameters::search_timeout},
      {"go_to_timeout", &TaskParameters::go_to_timeout},
      {"greet_timeout", &TaskParameters::greet_timeout},
      {"greet_distance", &TaskParameters::greet_distance},
      {"greet_cooldown", &TaskParameters::greet_cooldown},
  };
  return fields;
}
const std::vector<std::pair<std::string, int TaskParameters::*>>& TaskParameters::namedInts()
{
  static const std::vector<std::pair<std::string, int TaskParameters::*>> fields = {
      {"occupied_threshold", &TaskParameters::occupied_threshold},
  };
  return fields;
}
}  // namespace biovision_tasks
