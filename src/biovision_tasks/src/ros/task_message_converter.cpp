#include "biovision_tasks/ros/task_message_converter.hpp"

#include <cmath>
#include <stdexcept>

namespace biovision_tasks
{
OccupancyMap TaskMessageConverter::fromMessage(const nav_msgs::OccupancyGrid& grid)
{
  const auto& q = grid.info.origin.orientation;
  if (std::abs(q.x) > 1e-6 || std::abs(q.y) > 1e-6 || std::abs(q.z) > 1e-6)
    throw std::invalid_argument("occupancy grid: a rotated origin is not supported");
  const size_t cells = static_cast<size_t>(grid.info.width) * grid.info.height;
  if (grid.data.size() != cells)
    throw std::invalid_argument("occupancy grid: " + std::to_string(grid.data.size()) + " cells for " +
                                std::to_string(grid.info.width) + " x " + std::to_string(grid.info.height));
  cv::Mat1b m(static_cast<int>(grid.info.height), static_cast<int>(grid.info.width));
  for (size_t i = 0; i < cells; ++i)
  {
    const int v = grid.data[i];
    m(static_cast<int>(i / grid.info.width),
      static_cast<int>(i % grid.info.width)) = v < 0 || v > 100 ? OccupancyMap::kUnknown
                                                                : static_cast<unsigned char>(v);
  }
  return OccupancyMap(m, grid.info.origin.position.x, grid.info.origin.position.y, grid.info.resolution);
}

std::vector<Percept::Object> TaskMessageConverter::rememberedObjects(const biovision_msgs::LtmItemArray& items)
{
  std::vector<Percept::Object> out;
  for (const auto& it : items.items)
    if ((it.kind == "object" || it.kind == "landmark") && !it.label.empty() && std::isfinite(it.position.x) &&
        std::isfinite(it.position.y))
      out.push_back({it.label, it.position.x, it.position.y, it.strength, it.last_seen.toSec()});
  return out;
}

biovision_msgs::TaskStatus TaskMessageConverter::toMessage(const TaskManager::Status& status)
{
  biovision_msgs::TaskStatus m;
  m.macro_task = status.macro_task;
  m.micro_task = status.micro_task;
  m.step = static_cast<uint32_t>(std::max(0, status.step));
  m.steps = static_cast<uint32_t>(std::max(0, status.steps));
  m.mode = status.mode;
  m.message = status.message;
  switch (status.state)
  {
    case TaskState::Running:
      m.state = biovision_msgs::TaskStatus::RUNNING;
      break;
    case TaskState::Succeeded:
      m.state = biovision_msgs::TaskStatus::SUCCEEDED;
      break;
    case TaskState::Failed:
    case TaskState::Cancelled:
      m.state = biovision_msgs::TaskStatus::FAILED;
      break;
    default:
      m.state = biovision_msgs::TaskStatus::IDLE;
  }
  return m;
}
}  // namespace biovision_tasks
