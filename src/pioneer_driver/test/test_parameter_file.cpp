#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>

#include "pioneer_driver/pioneer_parameters.hpp"

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

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
