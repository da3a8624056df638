// rostest: base_controller in the simulator drives to a goal around a box and stops there; the watchdog
// stops the base within 0.5 s when the STM stops.
//
// The STM (memory/stm) is published by this test node from the simulator's ground truth (FloorPlan ranges
// of the same world file, all 9 sectors, at 10 Hz), because biovision_memory's disparity STM is not on
// this branch yet; the coordinator will switch the test to the memory node.
#include <atomic>
#include <cmath>
#include <iostream>
#include <mutex>
#include <string>

#include <biovision_msgs/AttractorState.h>
#include <biovision_msgs/EgoMap.h>
#include <biovision_msgs/PioneerState.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/Twist.h>
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <std_msgs/String.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>

#include "biovision_attractor/forcelets.hpp"
#include "biovision_ros_common/rostest_helpers.hpp"
#include "biovision_sim/floor_plan.hpp"
#include "biovision_sim/world.hpp"

using biovision_ros_common::waitFor;

namespace
{
class Harness
{
public:
  Harness() : plan_(biovision_sim::World::load(ros::NodeHandle("~").param<std::string>("world", "")))
  {
    stm_pub_ = nh_.advertise<biovision_msgs::EgoMap>("memory/stm", 5);
    goal_pub_ = nh_.advertise<geometry_msgs::PoseStamped>("goal", 1, true);
    pose_sub_ = nh_.subscribe("sim/ground_truth/pose", 10, &Harness::onPose, this);
    cmd_sub_ = nh_.subscribe("cmd_vel", 50, &Harness::onCmd, this);
    collision_sub_ = nh_.subscribe("sim/collision", 10, &Harness::onCollision, this);
    state_sub_ = nh_.subscribe("attractor/base", 10, &Harness::onState, this);
    stm_timer_ = nh_.createTimer(ros::Duration(0.1), &Harness::publishStm, this);
  }

  void publishStm(const ros::TimerEvent&)
  {
    if (!publish_stm_)
      return;
    geometry_msgs::PoseStamped pose;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!have_pose_)
        return;
      pose = pose_;
    }
    const double yaw = 2 * std::atan2(pose.pose.orientation.z, pose.pose.orientation.w);
    biovision_msgs::EgoMap map;
    map.header.stamp = ros::Time::now();
    map.header.frame_id = "base_link";
    map.section_width = static_cast<float>(M_PI / 9);
    map.max_range = 3.0f;
    for (int i = 0; i < 9; ++i)
    {
      const double centre = biovision_attractor::sectorCentre(i, 9, M_PI);
      double nearest = std::numeric_limits<double>::infinity();
      for (int r = -10; r <= 10; ++r)
        nearest = std::min(nearest,
                           plan_.range(pose.pose.position.x, pose.pose.position.y, yaw + centre + r * M_PI / 180, 3.0));
      map.section_angles.push_back(static_cast<float>(centre));
      map.obstacle_distance.push_back(static_cast<float>(nearest));
      map.confidence.push_back(1.0f);
    }
    if (future_stm_)
      map.header.stamp += ros::Duration(5.0);
    stm_pub_.publish(map);
    last_stm_ = ros::Time::now();
  }

  void onPose(const geometry_msgs::PoseStampedConstPtr& msg)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pose_ = *msg;
    have_pose_ = true;
  }
  void onCmd(const geometry_msgs::TwistConstPtr& msg)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    last_cmd_ = *msg;
    last_cmd_time_ = ros::Time::now();
    ++cmds_;
    if (msg->linear.x > max_linear_)
      max_linear_ = msg->linear.x;
    if (msg->linear.x == 0 && msg->angular.z == 0 && first_zero_.isZero() && !publish_stm_)
      first_zero_ = ros::Time::now();
  }
  void onCollision(const std_msgs::StringConstPtr&) { ++collisions_; }
  void onState(const biovision_msgs::AttractorStateConstPtr& msg)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    behaviour_ = msg->behaviour;
  }

  double distanceTo(double x, double y)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::hypot(pose_.pose.position.x - x, pose_.pose.position.y - y);
  }
  double lateral()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return pose_.pose.position.y;
  }
  geometry_msgs::Twist lastCmd()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return last_cmd_;
  }
  std::string behaviour()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return behaviour_;
  }
  void sendGoal(double x, double y, const std::string& frame)
  {
    geometry_msgs::PoseStamped g;
    g.header.frame_id = frame;
    g.header.stamp = ros::Time::now();
    g.pose.position.x = x;
    g.pose.position.y = y;
    g.pose.orientation.w = 1;
    goal_pub_.publish(g);
  }

  ros::NodeHandle nh_;
  biovision_sim::FloorPlan plan_;
  ros::Publisher stm_pub_, goal_pub_;
  std::mutex mutex_;
  geometry_msgs::PoseStamped pose_;
  bool have_pose_ = false;
  geometry_msgs::Twist last_cmd_;
  ros::Time last_cmd_time_, first_zero_, last_stm_;
  double max_linear_ = 0;
  std::string behaviour_;
  std::atomic<int> collisions_{0}, cmds_{0};
  std::atomic<bool> publish_stm_{true}, future_stm_{false};
  // Last: destroyed first (unsubscribing waits for a callback in progress), so no spinner thread writes
  // into the members above once they are gone.
  ros::Subscriber pose_sub_, cmd_sub_, collision_sub_, state_sub_;
  ros::Timer stm_timer_;
};
}  // namespace

TEST(BaseControllerNode, DrivesAroundTheBoxToTheGoalStopsThereAndTheWatchdogStopsIt)
{
  Harness h;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  ASSERT_TRUE(waitFor([&] { return h.have_pose_ && h.last_stm_.toSec() > 0; }, 30.0)) << "no simulator";

  // The goal in `map` (the simulator's static map -> odom): the controller goes through tf.
  h.sendGoal(4.0, 0.0, "map");
  double widest = 0;
  const bool reached = waitFor(
      [&] {
        widest = std::max(widest, std::abs(h.lateral()));
        const auto c = h.lastCmd();
        return h.distanceTo(4.0, 0.0) < 0.3 && c.linear.x == 0 && c.angular.z == 0 && h.behaviour() == "reached";
      },
      60.0);
  EXPECT_TRUE(reached) << "distance to the goal " << h.distanceTo(4.0, 0.0) << " m, behaviour " << h.behaviour();
  EXPECT_EQ(h.collisions_, 0);
  EXPECT_GT(widest, 0.4) << "went around the box (0.3 m half width + 0.26 m radius), not through it";
  EXPECT_LE(h.max_linear_, 0.5) << "cmd_vel within max_linear";
  // It stays there.
  ros::WallDuration(1.0).sleep();
  EXPECT_LT(h.distanceTo(4.0, 0.0), 0.3);

  // Drive on towards a far goal, then stop the STM: the base must be commanded zero within 0.5 s.
  h.sendGoal(8.0, 0.0, "odom");
  ASSERT_TRUE(waitFor([&] { return h.lastCmd().linear.x > 0.2; }, 20.0)) << "did not drive off again";
  h.publish_stm_ = false;
  const ros::Time stopped = h.last_stm_;
  ASSERT_TRUE(waitFor([&] { return !h.first_zero_.isZero(); }, 5.0)) << "the watchdog never zeroed cmd_vel";
  const double delay = (h.first_zero_ - stopped).toSec();
  std::cout << "watchdog: cmd_vel zeroed " << delay << " s (sim time) after the last STM" << std::endl;
  testing::Test::RecordProperty("watchdog_delay_s", std::to_string(delay));
  EXPECT_LE(delay, 0.5) << "cmd_vel zeroed " << delay << " s (sim time) after the last STM";
  EXPECT_GT(delay, 0.0);
  EXPECT_TRUE(waitFor([&] { return h.behaviour() == "watchdog" || h.lastCmd().linear.x == 0; }, 2.0));
  // It stays stopped while no STM comes.
  ros::WallDuration(0.5).sleep();
  EXPECT_EQ(h.lastCmd().linear.x, 0.0);
  EXPECT_EQ(h.collisions_, 0);
}

// Runs after the test above (gtest keeps declaration order): the controller still holds the goal 8 m ahead,
// stopped by the watchdog; fresh STM lets it drive again.
TEST(BaseControllerNode, HoldStopAndBadInputStopTheBase)
{
  Harness h;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  biovision_ros_common::DiagnosticsWatch diagnostics(h.nh_, "base controller");
  ASSERT_TRUE(waitFor([&] { return h.lastCmd().linear.x > 0.1; }, 20.0)) << "fresh STM: drives on to the goal";

  std_srvs::SetBool hold;
  hold.request.data = true;
  ASSERT_TRUE(ros::service::call("base/hold", hold));
  EXPECT_TRUE(waitFor([&] { return h.behaviour() == "hold" && h.lastCmd().linear.x == 0; }, 3.0));
  hold.request.data = false;
  ASSERT_TRUE(ros::service::call("base/hold", hold));
  EXPECT_TRUE(waitFor([&] { return h.lastCmd().linear.x > 0.05; }, 10.0)) << "resumes after hold";

  // A NaN goal: refused with an ERROR, the base stops.
  diagnostics.clear();
  h.sendGoal(std::nan(""), 0.0, "odom");
  EXPECT_TRUE(waitFor([&] { return diagnostics.sawError(); }, 5.0)) << "no ERROR for a NaN goal";
  EXPECT_TRUE(waitFor([&] { return h.lastCmd().linear.x == 0 && h.lastCmd().angular.z == 0; }, 3.0));

  // A goal in a frame tf does not know: refused, stopped.
  h.sendGoal(8.0, 0.0, "odom");
  ASSERT_TRUE(waitFor([&] { return h.lastCmd().linear.x > 0.05; }, 10.0));
  diagnostics.clear();
  h.sendGoal(8.0, 0.0, "nowhere");
  EXPECT_TRUE(waitFor([&] { return diagnostics.sawError(); }, 5.0)) << "no ERROR for an unknown frame";
  EXPECT_TRUE(waitFor([&] { return h.lastCmd().linear.x == 0; }, 3.0));

  // STM stamped 5 s in the future: rejected with an ERROR; without usable STM the watchdog stops the base.
  h.sendGoal(8.0, 0.0, "odom");
  ASSERT_TRUE(waitFor([&] { return h.lastCmd().linear.x > 0.05; }, 10.0));
  diagnostics.clear();
  h.future_stm_ = true;
  EXPECT_TRUE(waitFor([&] { return diagnostics.sawError() && h.behaviour() == "watchdog"; }, 5.0))
      << "behaviour " << h.behaviour();
  EXPECT_EQ(h.lastCmd().linear.x, 0.0);
  h.future_stm_ = false;

  // A bumper (pioneer_driver's pioneer_state): stops the base and forgets the goal.
  ASSERT_TRUE(waitFor([&] { return h.lastCmd().linear.x > 0.05; }, 10.0));
  ros::Publisher bumper = h.nh_.advertise<biovision_msgs::PioneerState>("pioneer_state", 1, true);
  biovision_msgs::PioneerState pressed;
  pressed.connected = pressed.motors_enabled = true;
  pressed.front_bumpers = 0x04;
  bumper.publish(pressed);
  EXPECT_TRUE(waitFor([&] { return h.behaviour() == "bumper" && h.lastCmd().linear.x == 0; }, 3.0))
      << "behaviour " << h.behaviour();
  pressed.front_bumpers = 0;
  bumper.publish(pressed);
  EXPECT_TRUE(waitFor([&] { return h.behaviour() == "idle"; }, 3.0)) << "released: the goal stays forgotten";
  EXPECT_EQ(h.lastCmd().linear.x, 0.0);

  // stop: zero at once and the goal forgotten (fresh STM does not restart it).
  h.sendGoal(8.0, 0.0, "odom");
  ASSERT_TRUE(waitFor([&] { return h.lastCmd().linear.x > 0.05; }, 10.0));
  std_srvs::Trigger stop;
  ASSERT_TRUE(ros::service::call("base/stop", stop));
  EXPECT_TRUE(stop.response.success);
  EXPECT_TRUE(waitFor([&] { return h.lastCmd().linear.x == 0 && h.lastCmd().angular.z == 0; }, 2.0));
  ros::WallDuration(1.0).sleep();
  EXPECT_EQ(h.lastCmd().linear.x, 0.0) << "stopped stays stopped";
  EXPECT_EQ(h.collisions_, 0);
}

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "test_base_controller_node", 0).run();  // the fixtures spin
}
