#include <gtest/gtest.h>

#include "biovision_ros_common/parameter_file_check.hpp"
#include "phantomx_driver/phantomx_parameters.hpp"

TEST(PhantomXParameterFile, TheYamlEqualsTheStructDefaultsKeyForKey)
{
  const auto problems = biovision_ros_common::yamlStructMismatches<phantomx_driver::PhantomXParameters>(
      std::string(BIOVISION_CONFIG_DIR) + "/phantomx_driver.yaml",
      [](auto& parameters, auto&& read) { phantomx_driver::visitParameters(parameters, read); });
  EXPECT_TRUE(problems.empty()) << biovision_ros_common::joinLines(problems);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
