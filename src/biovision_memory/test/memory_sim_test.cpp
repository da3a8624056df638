// The memory nodelet in the simulator: its STM matches the world's ground truth, its LTM holds the
// table-top, and an object reported by recognition is remembered where it is, then listed and forgotten.
#include <cmath>
#include <string>

#include <biovision_msgs/EgoMap.h>
#include <biovision_msgs/ForgetObject.h>
#include <biovision_msgs/ListMemoryObjects.h>
#include <biovision_msgs/QueryObject.h>
#include <biovision_msgs/RecognizedObjectArray.h>
#include <gtest/gtest.h>
#include <nav_msgs/OccupancyGrid.h>
#include <ros/ros.h>
#include <std_msgs/Float64.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include "biovision_ros_common/rostest_helpers.hpp"
#include "biovision_sim/floor_plan.hpp"

using biovision_ros_common::TopicProbe;
using biovision_ros_common::waitFor;

namespace
{
std::string worldFile()
{
  std::string w;
  ros::param::get("~world", w);
  return w;
}
}  // namespace

class MemorySim : public ::testing::Test
{
protected:
  void SetUp() override
  {
    tilt_pub_ = nh_.advertise<std_msgs::Float64>("head_tilt_joint/command", 1, true);
    std_msgs::Float64 tilt;
    tilt.data = 0.3;  // down, to see the floor and the table (the thesis' fixed tilt while driving)
    tilt_pub_.publish(tilt);
  }
  ros::NodeHandle nh_;
  ros::Publisher tilt_pub_;
};

TEST_F(MemorySim, StmMatchesGroundTruthAndLtmHoldsTheTable)
{
  const biovision_sim::World world = biovision_sim::World::load(worldFile());
  const biovision_sim::FloorPlan plan(world);
  TopicProbe<biovision_msgs::EgoMap> stm(nh_, "memory/stm");
  TopicProbe<nav_msgs::OccupancyGrid> ltm(nh_, "memory/ltm");
  ASSERT_TRUE(stm.waitForCount(40, 60.0)) << "no memory/stm";  // 4 s of sim time: the tilt has settled
  const auto map = stm.last();
  ASSERT_EQ(map->obstacle_distance.size(), 9u);
  EXPECT_EQ(map->header.frame_id, "base_link");
  // The base stands at the origin facing +x; the camera sees ±21.5° around pan 0.
  const double half_fov = 21.5 * M_PI / 180.0;
  int checked = 0;
  for (size_t i = 0; i < 9; ++i)
  {
    if (map->confidence[i] <= 0.5)
      continue;
    const double lo = std::max(map->section_angles[i] - map->section_width / 2, static_cast<float>(-half_fov));
    const double hi = std::min(map->section_angles[i] + map->section_width / 2, static_cast<float>(half_fov));
    double truth = INFINITY;
    for (double b = lo; b <= hi; b += 0.005)
      truth = std::min(truth, plan.range(0.0, 0.0, b, map->max_range));
    SCOPED_TRACE("sector " + std::to_string(i) + ", truth " + std::to_string(truth));
    if (truth < 1.5)
    {
      EXPECT_TRUE(std::isfinite(map->obstacle_distance[i])) << "missed an obstacle within 1.5 m";
    }
    if (std::isfinite(map->obstacle_distance[i]))
    {
      EXPECT_NEAR(map->obstacle_distance[i], truth, 0.15);
    }
    ++checked;
  }
  EXPECT_GE(checked, 1);
  EXPECT_NEAR(map->obstacle_distance[4], 0.7, 0.1) << "the table's front edge, straight ahead";

  ASSERT_TRUE(waitFor(
      [&] {
        const auto g = ltm.last();
        if (!g)
          return false;
        int n = 0;
        for (int8_t v : g->data)
          n += v > 0;
        return n >= 30;
      },
      30.0))
      << "the LTM did not fill";
  const auto grid = ltm.last();
  EXPECT_EQ(grid->header.frame_id, "map");
  int occupied = 0, near_truth = 0, on_table = 0;
  for (uint32_t r = 0; r < grid->info.height; ++r)
    for (uint32_t c = 0; c < grid->info.width; ++c)
    {
      if (grid->data[r * grid->info.width + c] <= 0)
        continue;
      const double x = grid->info.origin.position.x + (c + 0.5) * grid->info.resolution;
      const double y = grid->info.origin.position.y + (r + 0.5) * grid->info.resolution;
      ++occupied;
      near_truth += plan.clearance(x, y) <= 0.15;
      on_table += plan.obstacleAt(x, y, 0.05) == "table";
    }
  EXPECT_GE(static_cast<double>(near_truth) / occupied, 0.9) << near_truth << " of " << occupied;
  EXPECT_GE(on_table, 10);
}

TEST_F(MemorySim, ARecognisedObjectIsRememberedListedQueriedAndForgotten)
{
  TopicProbe<visualization_msgs::MarkerArray> truth(nh_, "sim/objects");
  ASSERT_TRUE(truth.waitForCount(1, 30.0));
  Eigen::Vector3d mug(NAN, NAN, NAN);
  for (const auto& m : truth.last()->markers)
    if (m.ns == "mug_red")
      mug = {m.pose.position.x, m.pose.position.y, m.pose.position.z};
  ASSERT_TRUE(mug.allFinite());
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  ros::Publisher objects = nh_.advertise<biovision_msgs::RecognizedObjectArray>("objects", 10);
  ASSERT_TRUE(waitFor([&] { return objects.getNumSubscribers() > 0; }, 20.0));
  // The camera's latest pose in map: messages are stamped where tf has it.
  const auto camera_from_map = [&](geometry_msgs::TransformStamped& t) {
    return waitFor(
        [&] {
          try
          {
            t = buffer.lookupTransform("stereo_left_optical", "map", ros::Time(0));
            return true;
          }
          catch (const tf2::TransformException&)
          {
            return false;
          }
        },
        10.0);
  };
  for (int i = 0; i < 6; ++i)
  {
    geometry_msgs::TransformStamped t;
    ASSERT_TRUE(camera_from_map(t));
    const Eigen::Vector3d in_optical = tf2::transformToEigen(t) * mug;
    biovision_msgs::RecognizedObjectArray msg;
    msg.header.frame_id = "stereo_left_optical";
    msg.header.stamp = t.header.stamp;
    biovision_msgs::RecognizedObject o;
    o.label = "mug_red";
    o.has_position = true;
    o.position.x = in_optical.x();
    o.position.y = in_optical.y();
    o.position.z = in_optical.z();
    msg.objects.push_back(o);
    objects.publish(msg);
    ros::WallDuration(0.3).sleep();
  }
  ros::ServiceClient query = nh_.serviceClient<biovision_msgs::QueryObject>("memory/query_object");
  biovision_msgs::QueryObject q;
  q.request.label = "mug_red";
  ASSERT_TRUE(waitFor([&] { return query.call(q) && q.response.found && q.response.observations >= 6; }, 10.0))
      << q.response.message;
  EXPECT_EQ(q.response.position.header.frame_id, "map");
  EXPECT_NEAR(q.response.position.point.x, mug.x(), 0.03);
  EXPECT_NEAR(q.response.position.point.y, mug.y(), 0.03);
  EXPECT_TRUE(q.response.landmark);  // 6 sightings: 40 + 5 × 40 = M_R
  EXPECT_FLOAT_EQ(q.response.confidence, 1.0f);

  ros::ServiceClient list = nh_.serviceClient<biovision_msgs::ListMemoryObjects>("memory/list_objects");
  biovision_msgs::ListMemoryObjects l;
  ASSERT_TRUE(list.call(l));
  ASSERT_EQ(l.response.items.size(), 1u);
  EXPECT_EQ(l.response.items[0].label, "mug_red");
  EXPECT_EQ(l.response.items[0].kind, "landmark");

  ros::ServiceClient forget = nh_.serviceClient<biovision_msgs::ForgetObject>("memory/forget_object");
  biovision_msgs::ForgetObject f;
  f.request.label = "mug_red";
  ASSERT_TRUE(forget.call(f));
  EXPECT_TRUE(f.response.success);
  ASSERT_TRUE(query.call(q));
  EXPECT_FALSE(q.response.found);

  // A position behind the camera (bad input: an error, the node keeps running), one deeper than
  // objects/max_depth (stereo too coarse there) and one far outside any camera's view at a plausible depth
  // (a corrupt x, 1e300 m): none is remembered.
  struct BadSighting
  {
    std::string label;
    double x, z;
  };
  for (const auto& [label, x, z] : {BadSighting{"behind_camera", 0.0, -1.0}, BadSighting{"too_deep", 0.0, 8.0},
                                    BadSighting{"outside_view", 1e300, 2.0}})
  {
    for (int i = 0; i < 3; ++i)
    {
      // Stamped where tf has the camera, as above: a "no transform" skip would hide what is tested.
      geometry_msgs::TransformStamped t;
      ASSERT_TRUE(camera_from_map(t));
      biovision_msgs::RecognizedObjectArray msg;
      msg.header.frame_id = "stereo_left_optical";
      msg.header.stamp = t.header.stamp;
      biovision_msgs::RecognizedObject o;
      o.label = label;
      o.has_position = true;
      o.position.x = x;
      o.position.z = z;
      msg.objects.push_back(o);
      objects.publish(msg);
      ros::WallDuration(0.3).sleep();
    }
  }
  for (const char* label : {"behind_camera", "too_deep", "outside_view"})
  {
    q.request.label = label;
    ASSERT_TRUE(query.call(q)) << label;  // still answering
    EXPECT_FALSE(q.response.found) << label;
  }
}

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "memory_sim_test", 2).run();
}
