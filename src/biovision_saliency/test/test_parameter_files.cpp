// The defaults of the saliency nodelet are written in three places a user reads — the core struct, the .cfg
// and config/*.yaml — so this test holds them equal, and every value the .cfg allows must pass validate().
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "biovision_ros_common/parameter_file_check.hpp"
#include "biovision_saliency/ros/saliency_config.hpp"

using namespace biovision_saliency;

TEST(ParameterFiles, YamlDefaultsEqualTheCfgDefaults)
{
  const auto problems = biovision_ros_common::yamlDefaultMismatches<SaliencyConfig>(BIOVISION_CONFIG_DIR
                                                                                    "/saliency.yaml");
  EXPECT_TRUE(problems.empty()) << biovision_ros_common::joinLines(problems);
}

TEST(ParameterFiles, CfgDefaultsEqualTheCoreDefaults)
{
  const SaliencyParameters cfg = toSaliencyParameters(SaliencyConfig::__getDefault__()), core;
  EXPECT_EQ(cfg.working_width, core.working_width);
  EXPECT_EQ(cfg.preferred_disparity_mode, core.preferred_disparity_mode);
  EXPECT_EQ(cfg.use_dis_flow, core.use_dis_flow);
  EXPECT_EQ(cfg.compensate_ego_motion, core.compensate_ego_motion);
  EXPECT_EQ(cfg.max_regions, core.max_regions);
  EXPECT_EQ(cfg.prior, core.prior);
  EXPECT_NEAR(cfg.prior_weight, core.prior_weight, 1e-4);
  EXPECT_NEAR(cfg.prior_sigma, core.prior_sigma, 1e-4 * std::max(1.0, core.prior_sigma));
  // A .cfg default is a decimal literal: 0.6667 stands for the core's 2/3.
  EXPECT_NEAR(cfg.colour_weight, core.colour_weight, 1e-4 * std::max(1.0, std::abs(core.colour_weight)));
  EXPECT_NEAR(cfg.disparity_weight, core.disparity_weight, 1e-4 * std::max(1.0, std::abs(core.disparity_weight)));
  EXPECT_NEAR(cfg.motion_weight, core.motion_weight, 1e-4 * std::max(1.0, std::abs(core.motion_weight)));
  EXPECT_NEAR(cfg.final_blur, core.final_blur, 1e-4 * std::max(1.0, std::abs(core.final_blur)));
  EXPECT_NEAR(cfg.near_fraction, core.near_fraction, 1e-4 * std::max(1.0, std::abs(core.near_fraction)));
  EXPECT_NEAR(cfg.preferred_disparity, core.preferred_disparity,
              1e-4 * std::max(1.0, std::abs(core.preferred_disparity)));
  EXPECT_NEAR(cfg.preferred_width, core.preferred_width, 1e-4 * std::max(1.0, std::abs(core.preferred_width)));
  EXPECT_NEAR(cfg.threshold, core.threshold, 1e-4 * std::max(1.0, std::abs(core.threshold)));
  EXPECT_NEAR(cfg.min_saliency, core.min_saliency, 1e-4 * std::max(1.0, std::abs(core.min_saliency)));
  EXPECT_NEAR(cfg.min_area, core.min_area, 1e-4 * std::max(1.0, std::abs(core.min_area)));
  EXPECT_NEAR(cfg.margin, core.margin, 1e-4 * std::max(1.0, std::abs(core.margin)));
  EXPECT_NEAR(cfg.ior_radius, core.ior_radius, 1e-4 * std::max(1.0, std::abs(core.ior_radius)));
  EXPECT_NEAR(cfg.ior_decay_time, core.ior_decay_time, 1e-4 * std::max(1.0, std::abs(core.ior_decay_time)));
  EXPECT_NEAR(cfg.attend_period, core.attend_period, 1e-4 * std::max(1.0, std::abs(core.attend_period)));
}

TEST(ParameterFiles, EveryValueTheCfgAllowsPassesValidate)
{
  const auto corners = biovision_ros_common::rangeCorners<SaliencyConfig>();
  ASSERT_GE(corners.size(), 20u);  // 2 per int/double parameter: the loop below must check something
  for (const auto& [label, config] : corners)
    EXPECT_NO_THROW(toSaliencyParameters(config).validate()) << label;
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
