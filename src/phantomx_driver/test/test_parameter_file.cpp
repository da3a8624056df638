#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>

#include "phantomx_driver/phantomx_parameters.hpp"

TEST(PhantomXParameterFile, TheYamlEqualsTheStructDefaultsKeyForKey)
{
  const YAML::Node yaml = YAML::LoadFile(std::string(BIOVISION_CONFIG_DIR) + "/phantomx_driver.yaml");
  phantomx_driver::PhantomXParameters defaults;
  std::set<std::string> names;
  phantomx_driver::visitParameters(defaults, [&](const std::string& name, auto& value) {
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
