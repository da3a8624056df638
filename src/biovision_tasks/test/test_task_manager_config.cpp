// The task manager's defaults are written once, in TaskParameters: config/task_manager.yaml and
// cfg/TaskManager.cfg must agree with it, and every value the .cfg allows must pass validate(). Also the
// message converter (GridMapRosConverter-style), testable without a master.
#include <gtest/gtest.h>

#include <biovision_tasks/TaskManagerConfig.h>

#include "biovision_ros_common/parameter_file_check.hpp"
#include "biovision_tasks/ros/task_manager_nodelet.hpp"
#include "biovision_tasks/ros/task_message_converter.hpp"

using namespace biovision_tasks;

TEST(TaskManagerConfig, YamlEqualsTheCfgDefaultsWhichEqualTheStruct)
{
  EXPECT_EQ(biovision_ros_common::joinLines(
                biovision_ros_common::yamlDefaultMismatches<TaskManagerConfig>(TASK_MANAGER_YAML)),
            "");
  const TaskParameters from_cfg = TaskManagerNodelet::parametersFromConfig(TaskManagerConfig::__getDefault__(), {});
  const TaskParameters defaults;
  for (const auto& [name, field] : TaskParameters::namedDoubles())
    EXPECT_EQ(from_cfg.*field, defaults.*field) << name;
  for (const auto& [name, field] : TaskParameters::namedInts())
    EXPECT_EQ(from_cfg.*field, defaults.*field) << name;
}

TEST(TaskManagerConfig, EveryCornerOfTheCfgRangesPassesValidate)
{
  for (const auto& [label, config] : biovision_ros_common::rangeCorners<TaskManagerConfig>())
    EXPECT_NO_THROW(TaskManagerNodelet::parametersFromConfig(config, {}).validate()) << label;
  TaskParameters bad;
  bad.goal_tolerance = -1;
  EXPECT_THROW(bad.validate(), std::invalid_argument);
}

TEST(TaskMessageConverter, OccupancyGridKeepsLayoutUnknownAndRefusesBadGrids)
{
  nav_msgs::OccupancyGrid g;
  g.info.width = 3;
  g.info.height = 2;
  g.info.resolution = 0.5;
  g.info.origin.position.x = -1;
  g.info.origin.position.y = 2;
  g.info.origin.orientation.w = 1;
  g.data = {0, 100, -1, 40, 0, 0};
  const OccupancyMap m = TaskMessageConverter::fromMessage(g);
  EXPECT_EQ(m.cells()(0, 1), 100);
  EXPECT_EQ(m.cells()(0, 2), OccupancyMap::kUnknown);
  EXPECT_EQ(m.cells()(1, 0), 40);
  int r, c;
  ASSERT_TRUE(m.cellOf(-0.4, 2.6, r, c));  // x in the second column, y in the second row
  EXPECT_EQ(r, 1);
  EXPECT_EQ(c, 1);
  g.data.pop_back();
  EXPECT_THROW(TaskMessageConverter::fromMessage(g), std::invalid_argument);
  g.data.push_back(0);
  g.info.origin.orientation.z = 0.7;
  EXPECT_THROW(TaskMessageConverter::fromMessage(g), std::invalid_argument);
  g.info.origin.orientation.z = 0;
  g.info.resolution = 0;
  EXPECT_THROW(TaskMessageConverter::fromMessage(g), std::invalid_argument);
}

TEST(TaskMessageConverter, RememberedObjectsAreTheLabelledObjectsAndLandmarks)
{
  biovision_msgs::LtmItemArray a;
  biovision_msgs::LtmItem i;
  i.kind = "obstacle";
  a.items.push_back(i);
  i.kind = "object";
  i.label = "cup";
  i.position.x = 1;
  i.strength = 0.5;
  a.items.push_back(i);
  i.kind = "landmark";
  i.label = "poster";
  i.position.x = std::nan("");
  a.items.push_back(i);
  const auto r = TaskMessageConverter::rememberedObjects(a);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].label, "cup");
  EXPECT_EQ(r[0].confidence, 0.5);
  TaskManager::Status s;
  s.state = TaskState::Cancelled;
  EXPECT_EQ(TaskMessageConverter::toMessage(s).state, biovision_msgs::TaskStatus::FAILED);
  EXPECT_EQ(TaskMessageConverter::toMessage(TaskManager::Status()).state, biovision_msgs::TaskStatus::IDLE);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
