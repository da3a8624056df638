// The monitor's defaults are written once, in MonitorParameters: config/monitor.yaml and cfg/Monitor.cfg
// must agree with them, and every .cfg range corner must pass validate().
#include <gtest/gtest.h>

#include "biovision_monitor/monitor_parameters.hpp"
#include "biovision_monitor/ros/monitor_config.hpp"
#include "biovision_ros_common/parameter_file_check.hpp"

using namespace biovision_monitor;

TEST(MonitorConfig, YamlEqualsTheCfgDefaults)
{
  const auto problems = biovision_ros_common::yamlDefaultMismatches<MonitorConfig>(MONITOR_YAML);
  EXPECT_TRUE(problems.empty()) << biovision_ros_common::joinLines(problems);
}

TEST(MonitorConfig, CfgDefaultsEqualTheStructDefaults)
{
  const MonitorParameters from_cfg = toMonitorParameters(MonitorConfig::__getDefault__());
  const MonitorParameters p;
  for (const auto& [name, field] : MonitorParameters::namedDoubles())
    EXPECT_EQ(from_cfg.*field, p.*field) << name;
  for (const auto& [name, field] : MonitorParameters::namedInts())
    EXPECT_EQ(from_cfg.*field, p.*field) << name;
  // Every field is a .cfg parameter.
  const auto d = biovision_ros_common::configDefaults<MonitorConfig>();
  EXPECT_EQ(d.doubles.size(), MonitorParameters::namedDoubles().size());
  EXPECT_EQ(d.ints.size(), MonitorParameters::namedInts().size());
}

TEST(MonitorConfig, EveryCfgRangeCornerIsValid)
{
  for (const auto& [label, config] : biovision_ros_common::rangeCorners<MonitorConfig>())
    EXPECT_NO_THROW(toMonitorParameters(config).validate()) << label;
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
