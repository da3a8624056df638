// The task_manager node on a real roscore: the tasks/execute action (success, failure with a reason,
// refusal of a bad task, preemption), the base goal it publishes, tasks/status, tasks/cancel, diagnostics.
#include <actionlib/client/simple_action_client.h>
#include <biovision_msgs/ExecuteTaskAction.h>
#include <biovision_msgs/TaskStatus.h>
#include <geometry_msgs/PoseStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "biovision_ros_common/rostest_helpers.hpp"

using biovision_ros_common::DiagnosticsWatch;
using biovision_ros_common::TopicProbe;
using biovision_ros_common::waitFor;
using Client = actionlib::SimpleActionClient<biovision_msgs::ExecuteTaskAction>;

namespace
{
biovision_msgs::ExecuteTaskGoal goal(const std::string& task, const std::vector<std::string>& arguments)
{
  biovision_msgs::ExecuteTaskGoal g;
  g.task = task;
  g.arguments = arguments;
  return g;
}
}  // namespace

TEST(TaskManagerNode, ExecutesCancelsAndRefusesTasks)
{
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  TopicProbe<geometry_msgs::PoseStamped> goals(nh, "goal");
  TopicProbe<biovision_msgs::TaskStatus> status(nh, "tasks/status");
  DiagnosticsWatch diagnostics(nh, "Task manager");
  Client client(nh, "tasks/execute", false);
  ASSERT_TRUE(client.waitForServer(ros::Duration(30)));
  ASSERT_TRUE(status.waitForCount(2, 10));

  // A wait succeeds.
  client.sendGoal(goal("wait", {"duration=0.5"}));
  ASSERT_TRUE(client.waitForResult(ros::Duration(10)));
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::SUCCEEDED);
  EXPECT_TRUE(client.getResult()->success);

  // A search that times out fails, saying why.
  client.sendGoal(goal("search", {"ghost", "timeout=1"}));
  ASSERT_TRUE(client.waitForResult(ros::Duration(10)));
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::ABORTED);
  EXPECT_NE(client.getResult()->message.find("'ghost' never found"), std::string::npos) << client.getResult()->message;

  // An unknown task is refused at once.
  client.sendGoal(goal("fly", {}));
  ASSERT_TRUE(client.waitForResult(ros::Duration(10)));
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::ABORTED);
  EXPECT_NE(client.getResult()->message.find("unknown task type 'fly'"), std::string::npos);

  // go_to publishes the goal in map and reports itself; preempting cancels it.
  const size_t before = goals.count();
  client.sendGoal(goal("go_to", {"x=4.5", "y=-1"}));
  ASSERT_TRUE(goals.waitForCount(before + 1, 10));
  const auto g = goals.last();
  EXPECT_EQ(g->header.frame_id, "map");
  EXPECT_NEAR(g->pose.position.x, 4.5, 1e-6);
  EXPECT_NEAR(g->pose.position.y, -1.0, 1e-6);
  ASSERT_TRUE(waitFor([&] { return status.last() && status.last()->state == biovision_msgs::TaskStatus::RUNNING; }, 5));
  EXPECT_EQ(status.last()->mode, "excursion");
  client.cancelGoal();
  ASSERT_TRUE(client.waitForResult(ros::Duration(10)));
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::PREEMPTED);

  // return_home: home is where the robot stood first; it is there, so it succeeds at once.
  client.sendGoal(goal("return_home", {}));
  ASSERT_TRUE(client.waitForResult(ros::Duration(10)));
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::SUCCEEDED);

  // tasks/cancel ends what is running.
  client.sendGoal(goal("look_around", {"duration=100"}));
  ASSERT_TRUE(waitFor([&] { return status.last() && status.last()->macro_task == "look_around"; }, 5));
  std_srvs::Trigger cancel;
  ASSERT_TRUE(ros::service::call("tasks/cancel", cancel));
  EXPECT_EQ(cancel.response.message, "cancelled");
  ASSERT_TRUE(client.waitForResult(ros::Duration(10)));
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::ABORTED);

  ASSERT_TRUE(waitFor([&] { return diagnostics.received() > 0; }, 5));
}

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "task_manager_node_test", 0).run();  // the fixtures spin
}
