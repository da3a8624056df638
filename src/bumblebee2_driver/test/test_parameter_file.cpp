#include <gtest/gtest.h>

#include "biovision_ros_common/parameter_file_check.hpp"
#include "bumblebee2_driver/bumblebee2_parameters.hpp"

TEST(Bumblebee2ParameterFile, TheYamlEqualsTheStructDefaultsKeyForKey)
{
  const auto problems = biovision_ros_common::yamlStructMismatches<bumblebee2_driver::Bumblebee2Parameters>(
      std::string(BIOVISION_CONFIG_DIR) + "/bumblebee2_driver.yaml",
      [](auto& parameters, auto&& read) { bumblebee2_driver::visitParameters(parameters, read); });
  EXPECT_TRUE(problems.empty()) << biovision_ros_common::joinLines(problems);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
