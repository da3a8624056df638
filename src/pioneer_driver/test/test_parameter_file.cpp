#include <gtest/gtest.h>

#include "biovision_ros_common/parameter_file_check.hpp"
#include "pioneer_driver/pioneer_parameters.hpp"
#include "pioneer_driver/ros/pioneer_driver_config.hpp"

TEST(PioneerParameterFile, TheYamlEqualsTheStructDefaultsKeyForKey)
{
  const auto problems = biovision_ros_common::yamlStructMismatches<pioneer_driver::PioneerParameters>(
      std::string(BIOVISION_CONFIG_DIR) + "/pioneer_driver.yaml",
      [](auto& parameters, auto&& read) { pioneer_driver::visitParameters(parameters, read); });
  EXPECT_TRUE(problems.empty()) << biovision_ros_common::joinLines(problems);
}

TEST(PioneerParameterFile, TheCfgDefaultsEqualTheYamlAndTheStruct)
{
  const auto problems = biovision_ros_common::yamlDefaultMismatches<pioneer_driver::PioneerDriverConfig>(
      std::string(BIOVISION_CONFIG_DIR) + "/pioneer_driver.yaml");
  EXPECT_TRUE(problems.empty()) << biovision_ros_common::joinLines(problems);
  const pioneer_driver::PioneerParameters core,
      cfg = pioneer_driver::withConfig(core, pioneer_driver::PioneerDriverConfig::__getDefault__());
  EXPECT_EQ(cfg.max_linear_speed, core.max_linear_speed);
  EXPECT_EQ(cfg.max_angular_speed, core.max_angular_speed);
  EXPECT_EQ(cfg.cmd_vel_timeout, core.cmd_vel_timeout);
}

TEST(PioneerParameterFile, EveryValueTheCfgAllowsValidates)
{
  const auto corners = biovision_ros_common::rangeCorners<pioneer_driver::PioneerDriverConfig>();
  ASSERT_EQ(corners.size(), 6u);
  for (const auto& [label, config] : corners)
    EXPECT_NO_THROW(pioneer_driver::withConfig({}, config).validate()) << label;
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
