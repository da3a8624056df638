// The defaults of biobin_disparity are written in three places a user reads — the core struct, the .cfg
// and config/*.yaml — so this test holds them equal, and every value the .cfg allows must pass validate().
#include <gtest/gtest.h>

#include "biovision_ros_common/parameter_file_check.hpp"
#include "biovision_stereo/ros/bio_bin_config.hpp"

using namespace biovision_stereo;

TEST(ParameterFiles, YamlDefaultsEqualTheCfgDefaults)
{
  const auto problems = biovision_ros_common::yamlDefaultMismatches<BioBinDisparityConfig>(BIOVISION_CONFIG_DIR
                                                                                           "/biobin_disparity.yaml");
  EXPECT_TRUE(problems.empty()) << biovision_ros_common::joinLines(problems);
}

TEST(ParameterFiles, CfgDefaultsEqualTheCoreDefaults)
{
  const BioBinParameters cfg = toBioBinParameters(BioBinDisparityConfig::__getDefault__()), core;
  EXPECT_EQ(cfg.wavelengths, core.wavelengths);
  EXPECT_EQ(cfg.max_disparity, core.max_disparity);
  EXPECT_EQ(cfg.kappa, core.kappa);
  EXPECT_EQ(cfg.tau, core.tau);
  EXPECT_EQ(cfg.alpha, core.alpha);
  EXPECT_EQ(cfg.beta, core.beta);
  EXPECT_EQ(cfg.sigma1, core.sigma1);
  EXPECT_EQ(cfg.sigma2, core.sigma2);
  EXPECT_EQ(cfg.fusion_level, core.fusion_level);
  EXPECT_EQ(cfg.relaxation, core.relaxation);
  EXPECT_EQ(cfg.stable_cost, core.stable_cost);
  EXPECT_EQ(cfg.max_iterations, core.max_iterations);
  EXPECT_EQ(cfg.line_edge_barriers, core.line_edge_barriers);
  EXPECT_EQ(cfg.subpixel, core.subpixel);
  EXPECT_EQ(cfg.left_right_check, core.left_right_check);
  EXPECT_EQ(cfg.left_right_tolerance, core.left_right_tolerance);
  EXPECT_EQ(cfg.fill_occlusions, core.fill_occlusions);
  EXPECT_EQ(cfg.median_filter, core.median_filter);
  EXPECT_EQ(cfg.aggregation, core.aggregation);
  EXPECT_EQ(cfg.sgm_p1, core.sgm_p1);
  EXPECT_EQ(cfg.sgm_p2, core.sgm_p2);
  EXPECT_EQ(cfg.sgm_p2_barrier, core.sgm_p2_barrier);
  EXPECT_EQ(cfg.sgm_paths, core.sgm_paths);
}

TEST(ParameterFiles, EveryValueTheCfgAllowsPassesValidate)
{
  const auto corners = biovision_ros_common::rangeCorners<BioBinDisparityConfig>();
  ASSERT_GE(corners.size(), 20u);  // 2 per int/double parameter: the loop below must check something
  for (const auto& [label, config] : corners)
    EXPECT_NO_THROW(toBioBinParameters(config).validate()) << label;
}

TEST(ParameterFiles, FastModeYamlIsAValidOverlay)
{
  const YAML::Node fast = YAML::LoadFile(BIOVISION_CONFIG_DIR "/biobin_fast.yaml");
  BioBinDisparityConfig config = BioBinDisparityConfig::__getDefault__();
  config.wavelengths = fast["wavelengths"].as<std::string>();
  config.max_disparity = fast["max_disparity"].as<int>();
  config.aggregation = fast["aggregation"].as<std::string>();
  EXPECT_NO_THROW(toBioBinParameters(config).validate());
  EXPECT_EQ(toBioBinParameters(config).aggregation, "iterative");
  EXPECT_EQ(toBioBinParameters(config).wavelengths, std::vector<double>{16.0});
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
