// The defaults of hri are written in three places a user reads — the core structs, the .cfg and
// config/hri.yaml — so this test holds them equal, and every value the .cfg allows must be accepted.
#include <gtest/gtest.h>

#include "biovision_ros_common/parameter_file_check.hpp"
#include "biovision_hri/ros/hri_config.hpp"

using namespace biovision_hri;

TEST(ParameterFiles, YamlDefaultsEqualTheCfgDefaults)
{
  const auto problems = biovision_ros_common::yamlDefaultMismatches<HriConfig>(BIOVISION_CONFIG_DIR "/hri.yaml");
  EXPECT_TRUE(problems.empty()) << biovision_ros_common::joinLines(problems);
}

TEST(ParameterFiles, CfgDefaultsEqualTheCoreDefaults)
{
  const HriParameters cfg = toHriParameters(HriConfig::__getDefault__(), GreetBehaviour::Parameters()), core;
  for (const auto& [c, d] : {std::make_pair(cfg.face, core.face), std::make_pair(cfg.hand, core.hand)})
  {
    EXPECT_EQ(c.stride, d.stride);
    EXPECT_EQ(c.max_cell_size, d.max_cell_size);
    EXPECT_EQ(c.nms_overlap, d.nms_overlap);
    EXPECT_EQ(c.threshold, d.threshold);
    EXPECT_EQ(c.min_size, d.min_size);
    EXPECT_EQ(c.max_size, d.max_size);
    EXPECT_EQ(c.max_detections, d.max_detections);
  }
  EXPECT_EQ(cfg.gestures.max_distance, core.gestures.max_distance);
  EXPECT_EQ(cfg.gestures.min_matches, core.gestures.min_matches);
  EXPECT_EQ(cfg.gestures.region_margin, core.gestures.region_margin);
  EXPECT_EQ(cfg.greet.look_up_tilt, core.greet.look_up_tilt);
  EXPECT_EQ(cfg.greet.search_timeout, core.greet.search_timeout);
  EXPECT_EQ(cfg.greet.lost_timeout, core.greet.lost_timeout);
  EXPECT_EQ(cfg.greet.gesture_timeout, core.greet.gesture_timeout);
  EXPECT_EQ(cfg.greet.centre_gain, core.greet.centre_gain);
  EXPECT_EQ(cfg.greet.centred_tolerance, core.greet.centred_tolerance);
  EXPECT_EQ(cfg.detection_width, core.detection_width);
  EXPECT_EQ(cfg.region_margin, core.region_margin);
  EXPECT_EQ(cfg.gesture_box_scale, core.gesture_box_scale);
}

TEST(ParameterFiles, EveryValueTheCfgAllowsIsAccepted)
{
  const auto corners = biovision_ros_common::rangeCorners<HriConfig>();
  ASSERT_GE(corners.size(), 30u);
  for (const auto& [label, config] : corners)
  {
    HriParameters p;
    ASSERT_NO_THROW(p = toHriParameters(config, GreetBehaviour::Parameters())) << label;
    // Sizes are checked as a pair (min <= max) by the nodelet, which refuses a crossed pair.
    for (auto* d : {&p.face, &p.hand})
      if (d->max_size < d->min_size)
        d->max_size = d->min_size;
    EXPECT_NO_THROW(p.face.validate()) << label;
    EXPECT_NO_THROW(p.hand.validate()) << label;
    EXPECT_NO_THROW(p.gestures.validate()) << label;
    EXPECT_NO_THROW(p.greet.validate()) << label;
  }
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
