// The defaults of v1_cells are written in three places a user reads — the core struct, the .cfg
// and config/*.yaml — so this test holds them equal, and every value the .cfg allows must build a pipeline.
#include <gtest/gtest.h>

#include "biovision_ros_common/parameter_file_check.hpp"
#include "biovision_v1/ros/v1_cells_config.hpp"

using namespace biovision_v1;

TEST(ParameterFiles, YamlDefaultsEqualTheCfgDefaults)
{
  const auto problems = biovision_ros_common::yamlDefaultMismatches<V1CellsConfig>(BIOVISION_CONFIG_DIR
                                                                                   "/v1_cells.yaml");
  EXPECT_TRUE(problems.empty()) << biovision_ros_common::joinLines(problems);
}

TEST(ParameterFiles, CfgDefaultsEqualTheCoreDefaults)
{
  const V1Pipeline::Parameters cfg = toV1Parameters(V1CellsConfig::__getDefault__()), core;
  EXPECT_EQ(cfg.gabor.wavelengths, core.gabor.wavelengths);
  EXPECT_EQ(cfg.gabor.orientations, core.gabor.orientations);
  EXPECT_EQ(cfg.gabor.sigma_per_wavelength, core.gabor.sigma_per_wavelength);
  EXPECT_EQ(cfg.gabor.aspect_ratio, core.gabor.aspect_ratio);
  EXPECT_EQ(cfg.gabor.min_grid_wavelength, core.gabor.min_grid_wavelength);
  EXPECT_EQ(cfg.keypoints.threshold, core.keypoints.threshold);
  EXPECT_EQ(cfg.keypoints.min_contrast, core.keypoints.min_contrast);
  EXPECT_EQ(cfg.keypoints.inhibition_gain, core.keypoints.inhibition_gain);
  EXPECT_EQ(cfg.keypoints.radial_factor, core.keypoints.radial_factor);
  EXPECT_EQ(cfg.keypoints.junction_weight, core.keypoints.junction_weight);
  EXPECT_EQ(cfg.keypoints.junction_balance, core.keypoints.junction_balance);
  EXPECT_EQ(cfg.keypoints.max_keypoints, core.keypoints.max_keypoints);
  EXPECT_EQ(cfg.line_edges.relative_threshold, core.line_edges.relative_threshold);
  EXPECT_EQ(cfg.line_edges.min_contrast, core.line_edges.min_contrast);
  EXPECT_EQ(cfg.line_edges.lateral_inhibition, core.line_edges.lateral_inhibition);
  EXPECT_EQ(cfg.end_stop_offset, core.end_stop_offset);
}

TEST(ParameterFiles, EveryValueTheCfgAllowsBuildsAPipeline)
{
  const auto corners = biovision_ros_common::rangeCorners<V1CellsConfig>();
  ASSERT_GE(corners.size(), 20u);  // 2 per int/double parameter: the loop below must check something
  for (const auto& [label, config] : corners)
    EXPECT_NO_THROW(V1Pipeline pipeline(toV1Parameters(config))) << label;
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
