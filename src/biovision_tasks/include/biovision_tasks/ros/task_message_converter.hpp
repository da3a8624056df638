#pragma once

#include <vector>

#include <biovision_msgs/LtmItemArray.h>
#include <biovision_msgs/TaskStatus.h>
#include <nav_msgs/OccupancyGrid.h>

#include "biovision_tasks/occupancy_map.hpp"
#include "biovision_tasks/percept.hpp"
#include "biovision_tasks/task_manager.hpp"

namespace biovision_tasks
{
/// The one place where the task manager's core types meet ROS messages (static, testable without a
/// master; grid_map's GridMapRosConverter is the model).
class TaskMessageConverter
{
public:
  /// nav_msgs/OccupancyGrid (row-major from the origin, -1 unknown, 0..100) → OccupancyMap. The grid's
  /// origin must not be rotated (the memory publishes axis-aligned maps). Throws std::invalid_argument on
  /// a rotated origin, a data size that is not width × height, or a non-positive or non-finite resolution.
  static OccupancyMap fromMessage(const nav_msgs::OccupancyGrid& grid);
  /// The objects and landmarks with a label in the long-term memory's items (kind "object" or "landmark"),
  /// as remembered objects; obstacles are skipped.
  static std::vector<Percept::Object> rememberedObjects(const biovision_msgs::LtmItemArray& items);
  /// The manager's status as biovision_msgs/TaskStatus (IDLE when nothing ever ran).
  static biovision_msgs::TaskStatus toMessage(const TaskManager::Status& status);
};
}  // namespace biovision_tasks
