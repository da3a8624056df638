#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>

#include "bumblebee2_driver/bumblebee2_parameters.hpp"

TEST(Bumblebee2ParameterFile, TheYamlEqualsTheStructDefaultsKeyForKey)
{
  const YAML::Node yaml = YAML::LoadFile(std::string(BIOVISION_CONFIG_DIR) + "/bumblebee2_driver.yaml");
  bumblebee2_driver::Bumblebee2Parameters defaults;
  std::set<std::string> names;
  bumblebee2_driver::visitParameters(defaults, [&](const std::string& name, auto& value) {
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
