// recognition's defaults are repeated for the user in config/recognition.yaml and cfg/Recognition.cfg:
// this test holds the two equal. (The core's ObjectRecognizer::Parameters keeps time_budget_ms = 0, no
// limit, on purpose: the evaluation tools measure whole queries; the node's 150 ms is a run-time budget.)
#include <gtest/gtest.h>

#include <biovision_recognition/RecognitionConfig.h>

#include "biovision_ros_common/parameter_file_check.hpp"

TEST(ParameterFiles, YamlDefaultsEqualTheCfgDefaults)
{
  const auto problems = biovision_ros_common::yamlDefaultMismatches<biovision_recognition::RecognitionConfig>(
      BIOVISION_CONFIG_DIR "/recognition.yaml");
  EXPECT_TRUE(problems.empty()) << biovision_ros_common::joinLines(problems);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
