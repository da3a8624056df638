// The task_manager node on a real roscore: the tasks/execute action (success, failure with a reason,
// refusal of a bad task, preemption), the base goal it publishes, tasks/status, tasks/cancel, diagnostics,
// and a greet through biovision_hri's services and action topic (the test stands in for the hri node).
#include <actionlib/client/simple_action_client.h>
#include <biovision_msgs/ExecuteTaskAction.h>
#include <biovision_msgs/SetHeadMode.h>
#include <biovision_msgs/TaskStatus.h>
#include <geometry_msgs/PoseStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_msgs/String.h>
#include <std_srvs/Trigger.h>
#include <ros/callback_queue.h>

#include <atomic>

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

// The head controller accepts head/set_mode and never answers (make demo, 2026-12-05: the task manager
// waited on that call for good, under its lock: no status, no goal, no cancel). The tasks go on: status
// every cycle, the cancel service answers, diagnostics name the call given up on.
TEST(TaskManagerNode, KeepsCyclingWhileTheHeadControllerNeverAnswers)
{
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  biovision_ros_common::HangingServiceServer<biovision_msgs::SetHeadMode> head("head/set_mode");
  TopicProbe<biovision_msgs::TaskStatus> status(nh, "tasks/status");
  DiagnosticsWatch diagnostics(nh, "Task manager");
  Client client(nh, "tasks/execute", false);
  ASSERT_TRUE(client.waitForServer(ros::Duration(30)));

  client.sendGoal(goal("look_around", {"duration=100"}));  // asks the head to explore
  ASSERT_TRUE(waitFor([&] { return head.entered() >= 1; }, 10));
  const size_t before = status.count();
  // 5 Hz cycles: 10 statuses in 2 s while the call hangs (none at all before the fix).
  ASSERT_TRUE(status.waitForCount(before + 10, 10)) << status.count() - before << " statuses";
  EXPECT_EQ(status.last()->macro_task, "look_around");
  ASSERT_TRUE(
      waitFor([&] { return diagnostics.lastValue("head/set_mode").find("no answer") != std::string::npos; }, 10))
      << diagnostics.lastValue("head/set_mode");
  EXPECT_EQ(diagnostics.lastValue("head/set_mode").rfind("explore: ", 0), 0u) << diagnostics.lastValue("head/set_mode");
  std_srvs::Trigger cancel;
  ASSERT_TRUE(ros::service::call("tasks/cancel", cancel));
  EXPECT_EQ(cancel.response.message, "cancelled");
  ASSERT_TRUE(client.waitForResult(ros::Duration(10)));
  head.release();
}

// base/stop answers 1.5 s late; a turn is sent while the first stop's call is under way, then a stop again.
// The late answer belongs to a stop the tasks have left behind: the new stop must call base/stop again
// (the breaker's race: the task manager took the late answer for the new stop and the base kept turning).
TEST(TaskManagerNode, ALateStopAnswerDoesNotCountForALaterStop)
{
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  ros::CallbackQueue queue;
  ros::NodeHandle server_nh;
  server_nh.setCallbackQueue(&queue);
  std::atomic<int> stops{0};
  ros::ServiceServer server = server_nh.advertiseService<std_srvs::Trigger::Request, std_srvs::Trigger::Response>(
      "base/stop", [&](std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
        ++stops;
        ros::WallDuration(1.5).sleep();
        res.success = true;
        return true;
      });
  ros::AsyncSpinner server_spinner(1, &queue);
  server_spinner.start();
  Client client(nh, "tasks/execute", false);
  ASSERT_TRUE(client.waitForServer(ros::Duration(30)));

  client.sendGoal(goal("stop", {"duration=0.4"}));
  ASSERT_TRUE(waitFor([&] { return stops >= 1; }, 10));
  const int before = stops;
  client.sendGoal(goal("turn", {"angle=1.0"}));  // a bearing goes out while base/stop is under way
  ros::WallDuration(0.5).sleep();
  client.sendGoal(goal("stop", {"duration=100"}));
  EXPECT_TRUE(waitFor([&] { return stops >= before + 1; }, 8)) << "the second stop never called base/stop";
  client.cancelGoal();
  server_spinner.stop();
}

// A greet calls hri/greet, ends on the hri/action published after it and then calls hri/stop_greet; the
// action's result names the gesture action.
TEST(TaskManagerNode, AGreetCallsTheHriNodeAndEndsOnItsGestureAction)
{
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  std::atomic<int> greets{0}, stops{0};
  ros::ServiceServer greet = nh.advertiseService<std_srvs::Trigger::Request, std_srvs::Trigger::Response>(
      "hri/greet", [&](std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
        ++greets;
        res.success = true;
        res.message = "greeting";
        return true;
      });
  ros::ServiceServer stop = nh.advertiseService<std_srvs::Trigger::Request, std_srvs::Trigger::Response>(
      "hri/stop_greet", [&](std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
        ++stops;
        res.success = true;
        return true;
      });
  ros::Publisher action = nh.advertise<std_msgs::String>("hri/action", 5);
  DiagnosticsWatch diagnostics(nh, "Task manager");
  Client client(nh, "tasks/execute", false);
  ASSERT_TRUE(client.waitForServer(ros::Duration(30)));

  client.sendGoal(goal("greet", {"timeout=30"}));
  ASSERT_TRUE(waitFor([&] { return greets >= 1; }, 10)) << "hri/greet was not called";
  EXPECT_FALSE(client.waitForResult(ros::Duration(0.5))) << "the greet ended before any gesture";
  std_msgs::String m;
  m.data = "continue";
  ASSERT_TRUE(waitFor(
      [&] {
        action.publish(m);
        return client.waitForResult(ros::Duration(0.2));
      },
      10));
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::SUCCEEDED);
  EXPECT_NE(client.getResult()->message.find("gesture action 'continue'"), std::string::npos)
      << client.getResult()->message;
  EXPECT_TRUE(waitFor([&] { return stops >= 1; }, 10)) << "hri/stop_greet was not called after the greet";
  EXPECT_EQ(greets, 1) << "one greet, one call";
  EXPECT_TRUE(waitFor([&] { return diagnostics.lastValue("last gesture action") == "continue"; }, 10));
}

int main(int argc, char** argv)
{
  return biovision_ros_common::RosTestRun(argc, argv, "task_manager_node_test", 0).run();  // the fixtures spin
}
