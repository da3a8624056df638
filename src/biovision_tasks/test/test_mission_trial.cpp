// mission_eval's trial in a world file (--world): the target where the world's object stood, the new crate
// put by mission_director's rule, and a world it cannot use refused before any trial.
#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "../tools/mission_trial.hpp"
#include "biovision_sim/floor_plan.hpp"
#include "biovision_sim/world.hpp"

using namespace biovision_tasks;

namespace
{
// A closed corridor 2.4 m wide opening into a 4 x 4 m room, the target in the room (the demo's layout, bare).
const char* kWorld = R"(name: test_corridor
objects:
  - {label: wall_left, shape: box, position: [3.0, 1.25, 1.0], size: [8.0, 0.1, 2.0]}
  - {label: wall_right, shape: box, position: [3.0, -1.25, 1.0], size: [8.0, 0.1, 2.0]}
  - {label: wall_back, shape: box, position: [-1.05, 0.0, 1.0], size: [0.1, 2.6, 2.0]}
  - {label: room_wall_far, shape: box, position: [9.0, 0.0, 1.0], size: [0.1, 4.0, 2.0]}
  - {label: room_wall_left, shape: box, position: [8.0, 2.0, 1.0], size: [2.0, 0.1, 2.0]}
  - {label: room_wall_right, shape: box, position: [8.0, -2.0, 1.0], size: [2.0, 0.1, 2.0]}
  - {label: room_wall_west_left, shape: box, position: [7.0, 1.625, 1.0], size: [0.1, 0.75, 2.0]}
  - {label: room_wall_west_right, shape: box, position: [7.0, -1.625, 1.0], size: [0.1, 0.75, 2.0]}
  - {label: target_box, shape: box, position: [8.0, 1.0, 0.2], size: [0.4, 0.3, 0.4]}
)";

std::string writeWorld(const std::string& name, const std::string& text)
{
  const std::string path = testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}
}  // namespace

TEST(MissionTrial, AWorldFilesTargetIsFoundAndTheNewCrateStandsClearOfEverything)
{
  MissionTrialOptions o;
  o.world_file = writeWorld("mission_world.yaml", kWorld);
  o.new_obstacles = 1;
  ASSERT_NO_THROW(checkMissionWorld(o));
  const MissionTrialResult r = runMissionTrial(1, TaskParameters(), {}, {}, o);
  ASSERT_TRUE(r.found) << r.outcome;
  EXPECT_LT(r.found_error, 0.5);
  EXPECT_NEAR(r.target.x, 8.0, 1e-9) << "the target where the world's target_box stood";
  EXPECT_NEAR(r.target.y, 1.0, 1e-9);
  EXPECT_NEAR(r.home.x, 0.0, 1e-9);
  EXPECT_LE(std::abs(r.home.y), o.start_jitter);
  // One crate, placed by mission_director's rule: 1 m clear of every footprint (the target's excepted), of the
  // robot and of home.
  ASSERT_EQ(r.new_obstacles_placed, 1);
  ASSERT_EQ(r.new_obstacle_positions.size(), 1u);
  const cv::Point2d crate = r.new_obstacle_positions[0];
  biovision_sim::World walls = biovision_sim::World::load(o.world_file);
  biovision_sim::World others;
  for (const auto& object : walls.objects())
    if (object.label != "target_box")
      others.addObject(object);
  EXPECT_GE(biovision_sim::FloorPlan(others).clearance(crate.x, crate.y), 1.0 - 1e-9);
  EXPECT_GE(cv::norm(crate - r.home), 1.0);
}

TEST(MissionTrial, AWorldWithoutItsTargetOrWithTheTargetOffTheMapIsRefused)
{
  MissionTrialOptions o;
  o.world_file = writeWorld("mission_world.yaml", kWorld);
  o.world_target = "no_such_object";
  EXPECT_THROW(checkMissionWorld(o), std::runtime_error);
  o.world_target = "target_box";
  o.world_file = writeWorld("mission_far.yaml",
                            "name: far\nobjects:\n  - {label: target_box, shape: box, position: "
                            "[30, 0, 0.2], size: [0.4, 0.3, 0.4]}\n");
  EXPECT_THROW(checkMissionWorld(o), std::runtime_error);
  o.world_file = writeWorld("mission_bad.yaml", "name: x\nobjects: [\n");
  EXPECT_THROW(checkMissionWorld(o), std::runtime_error);
  const std::string walls = std::string(kWorld).substr(0, std::string(kWorld).find("  - {label: target_box"));
  for (const char* target : {
           "  - {label: target_box, shape: box, position: [0.5, 0.0, 0.2], size: [0.4, 0.3, 0.4]}\n",   // at the start
           "  - {label: target_box, shape: box, position: [3.0, 1.25, 0.2], size: [0.4, 0.3, 0.4]}\n",  // in a wall
           "  - {label: target_box, shape: box, position: [5.0, 0.0, 0.2], size: [8.0, 0.3, 0.4]}\n",   // 8 m wide
       })
  {
    o.world_file = writeWorld("mission_target.yaml", walls + target);
    EXPECT_THROW(checkMissionWorld(o), std::runtime_error) << target;
  }
  o.world_file = writeWorld("mission_two.yaml", std::string(kWorld) +
                                                    "  - {label: target_box, shape: box, position: "
                                                    "[6.0, 0.0, 0.2], size: [0.4, 0.3, 0.4]}\n");
  EXPECT_THROW(checkMissionWorld(o), std::runtime_error) << "two targets";
  o.world_file = writeWorld("mission_start.yaml", std::string(kWorld) +
                                                      "  - {label: post, shape: cylinder, position: "
                                                      "[0.0, 0.2, 0.5], radius: 0.1, height: 1}\n");
  EXPECT_THROW(checkMissionWorld(o), std::runtime_error) << "the start beside a post";
  o.world_file = "/dev/zero";
  EXPECT_THROW(checkMissionWorld(o), std::runtime_error) << "not a regular file";
  o.world_file.clear();  // the generated rooms: nothing to check
  EXPECT_NO_THROW(checkMissionWorld(o));
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
