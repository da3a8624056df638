// config/memory.yaml holds the same defaults as the parameter structs and the nodelet's Settings
// (a drifted value fails here).
#include <string>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "biovision_memory/landmark_corrector.hpp"
#include "biovision_memory/long_term_memory.hpp"
#include "biovision_memory/object_memory.hpp"
#include "biovision_memory/ros/memory_nodelet.hpp"
#include "biovision_memory/short_term_memory_parameters.hpp"

using namespace biovision_memory;

TEST(ParameterFile, MemoryYamlEqualsTheDefaults)
{
  const YAML::Node y = YAML::LoadFile(MEMORY_YAML);
  const MemoryNodelet::Settings s;
  EXPECT_EQ(y["lazy"].as<bool>(), false);
  EXPECT_EQ(y["map_frame"].as<std::string>(), s.map_frame);
  EXPECT_EQ(y["odom_frame"].as<std::string>(), s.odom_frame);
  EXPECT_EQ(y["base_frame"].as<std::string>(), s.base_frame);
  EXPECT_EQ(y["database"].as<std::string>(), s.database);
  EXPECT_EQ(y["start_empty_on_bad_database"].as<bool>(), s.start_empty_on_bad_database);
  EXPECT_EQ(y["start_empty"].as<bool>(), s.start_empty);
  EXPECT_DOUBLE_EQ(y["save_period"].as<double>(), s.save_period);
  EXPECT_DOUBLE_EQ(y["ltm_period"].as<double>(), s.ltm_period);
  EXPECT_DOUBLE_EQ(y["publish_period"].as<double>(), s.publish_period);
  EXPECT_DOUBLE_EQ(y["disparity_timeout"].as<double>(), s.disparity_timeout);
  EXPECT_DOUBLE_EQ(y["tf_timeout"].as<double>(), s.tf_timeout);
  EXPECT_EQ(y["landmark_correction"].as<bool>(), s.landmark_correction);
  EXPECT_EQ(y["publish_map_to_odom"].as<bool>(), s.publish_map_to_odom);
  EXPECT_DOUBLE_EQ(y["map_to_odom_rate"].as<double>(), s.map_to_odom_rate);

  const ShortTermMemoryParameters stm;
  const YAML::Node m = y["stm"];
  EXPECT_DOUBLE_EQ(m["max_range"].as<double>(), stm.scan.max_range);
  EXPECT_DOUBLE_EQ(m["min_obstacle_height"].as<double>(), stm.scan.min_obstacle_height);
  EXPECT_DOUBLE_EQ(m["max_obstacle_height"].as<double>(), stm.scan.max_obstacle_height);
  EXPECT_EQ(m["strips"].as<int>(), stm.scan.strips);
  EXPECT_EQ(m["min_obstacle_pixels"].as<int>(), stm.scan.min_obstacle_pixels);
  EXPECT_DOUBLE_EQ(m["min_valid_fraction"].as<double>(), stm.scan.min_valid_fraction);
  EXPECT_DOUBLE_EQ(m["bin_width"].as<double>(), stm.scan.bin_width);
  EXPECT_EQ(m["pixel_step"].as<int>(), stm.scan.pixel_step);
  EXPECT_EQ(m["sectors"].as<int>(), stm.sectors);
  EXPECT_NEAR(m["sector_width"].as<double>(), stm.sector_width, 1e-12);
  EXPECT_DOUBLE_EQ(m["obstacle_horizon_time"].as<double>(), stm.obstacle_horizon_time);
  EXPECT_DOUBLE_EQ(m["free_horizon_time"].as<double>(), stm.free_horizon_time);
  EXPECT_DOUBLE_EQ(m["horizon_distance"].as<double>(), stm.horizon_distance);
  EXPECT_DOUBLE_EQ(m["map_completion_radius"].as<double>(), stm.map_completion_radius);

  const LongTermMemoryParameters ltm;
  const YAML::Node l = y["ltm"];
  EXPECT_EQ(l["initial_strength"].as<int>(), ltm.rules.initial_strength);
  EXPECT_EQ(l["reinforcement"].as<int>(), ltm.rules.reinforcement);
  EXPECT_EQ(l["max_strength"].as<int>(), ltm.rules.max_strength);
  EXPECT_EQ(l["penalty"].as<int>(), ltm.rules.penalty);
  EXPECT_DOUBLE_EQ(l["forget_period"].as<double>(), ltm.rules.forget_period);
  EXPECT_DOUBLE_EQ(l["cell_size"].as<double>(), ltm.cell_size);
  EXPECT_EQ(l["min_points"].as<int>(), ltm.min_points);
  EXPECT_DOUBLE_EQ(l["free_margin"].as<double>(), ltm.free_margin);

  const ObjectMemoryParameters objects;
  EXPECT_DOUBLE_EQ(y["objects"]["match_distance"].as<double>(), objects.match_distance);
  EXPECT_EQ(y["objects"]["averaging_window"].as<int>(), objects.averaging_window);
  EXPECT_DOUBLE_EQ(y["objects"]["max_depth"].as<double>(), objects.max_depth);

  const LandmarkCorrectorParameters c;
  const YAML::Node k = y["landmarks"];
  EXPECT_EQ(k["window"].as<int>(), c.window);
  EXPECT_DOUBLE_EQ(k["window_time"].as<double>(), c.window_time);
  EXPECT_DOUBLE_EQ(k["gain"].as<double>(), c.gain);
  EXPECT_DOUBLE_EQ(k["min_spread"].as<double>(), c.min_spread);
  EXPECT_DOUBLE_EQ(k["max_jump"].as<double>(), c.max_jump);
  EXPECT_DOUBLE_EQ(k["max_depth"].as<double>(), c.max_depth);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
