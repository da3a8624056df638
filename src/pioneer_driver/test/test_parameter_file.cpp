#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>

#include "biovision_ros_common/parameter_file_check.hpp"
#include "pioneer_driver/pioneer_parameters.hpp"
#include "pioneer_driver/ros/pioneer_driver_config.hpp"

TEST(PioneerParameterFile, TheYamlEqualsTheStructDefaultsKeyForKey)
{
  const YAML::Node yaml = YAML::LoadFile(std::string(BIOVISION_CONFIG_DIR) + "/pioneer_driver.yaml");
  pioneer_driver::PioneerParameters defaults;
  std::set<std::string> names;
  pioneer_driver::visitParameters(defaults, [&](const std::string& name, auto& value) {
    names.insert(name);
    ASSERT_TRUE(yaml[name]) << name << " missing from the YAML";
    using T = std::decay_t<decltype(value)>;
    const T got = yaml[name].as<T>();
    if constexpr (std::is_floating_point_v<T>)
      EXPECT_NEAR(got, value, 1e-12) << name;
    else
      EXPECT_EQ(got, value) << name;
  });
  for (const auto& kv : yaml)
    EXPECT_TRUE(names.count(kv.first.as<std::string>())) << kv.first.as<std::string>() << " is not a parameter";
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
