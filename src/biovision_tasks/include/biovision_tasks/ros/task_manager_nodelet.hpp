#pragma once

#include <deque>
#include <memory>
#include <mutex>
#include <set>
#include <string>

#include <actionlib/server/simple_action_server.h>
#include <biovision_msgs/AttractorState.h>
#include <biovision_msgs/ExecuteTaskAction.h>
#include <biovision_msgs/LtmItemArray.h>
#include <biovision_msgs/RecognizedObjectArray.h>
#include <biovision_tasks/TaskManagerConfig.h>
#include <dynamic_reconfigure/server.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nodelet/nodelet.h>
#include <ros/ros.h>
#include <std_msgs/String.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <boost/thread/recursive_mutex.hpp>

#include <biovision_msgs/SetHeadMode.h>

#include "biovision_ros_common/async_service_client.hpp"
#include "biovision_ros_common/nodelet_diagnostics.hpp"
#include "biovision_tasks/task_manager.hpp"

namespace biovision_tasks
{
/// The task manager (thesis §5.3.3) on ROS: TaskManager steps at ~rate in ROS time.
/// Nodelet biovision_tasks/TaskManagerNodelet; the node `task_manager` runs it alone.
///
/// In: tf ~map_frame → ~base_frame (older than ~pose_timeout = no localisation: the base is stopped),
/// tf ~map_frame → ~camera_frame (an optical frame, z = viewing direction: where the camera looks, for the
/// exploration's coverage; missing: all round),
/// `objects` (biovision_msgs/RecognizedObjectArray, positions in the camera frame, placed in map through
/// tf; "in view" for ~seen_hold s), `memory/ltm` (nav_msgs/OccupancyGrid), `memory/ltm_items`
/// (biovision_msgs/LtmItemArray: remembered objects), `attractor/base` (biovision_msgs/AttractorState of the
/// base controller: behaviour "trapped" or a stop/fault behaviour tells the tasks).
/// Out: `goal` (geometry_msgs/PoseStamped in map: the active visuomotor cycle's goal, sent when it moves
/// by more than 5 cm or every ~goal_refresh s — each goal restarts the base's trap detector, so not every
/// cycle), `goal_bearing` (std_msgs/Float64 [rad] relative to the heading: a turn), the base controller's
/// `base/stop` service when the command is to stop, the head controller's `head/set_mode` service on a mode change
/// (both called off the task cycle, AsyncServiceClient: a call unanswered within ~service_timeout s is given up,
/// reported in diagnostics and made again; the cycle never waits on a service),
/// `tasks/status` (biovision_msgs/TaskStatus, every cycle), `/diagnostics`.
/// Action `tasks/execute` (biovision_msgs/ExecuteTask): task = a task type and arguments its object and
/// key=value pairs (TaskSpec::parseText), or task "mission" with arguments[0] a mission YAML file; the
/// result comes when all its tasks have finished (success = all succeeded); preempting cancels them.
/// Service `tasks/cancel` (std_srvs/Trigger) cancels everything. ~mission: a mission file run at start.
/// A backward jump of ROS time cancels every task (and aborts the action) and forgets the mission record.
class TaskManagerNodelet : public nodelet::Nodelet
{
public:
  ~TaskManagerNodelet() override;
  /// `base` with every field the config names replaced by the config's value.
  static TaskParameters parametersFromConfig(const TaskManagerConfig& config, TaskParameters base);

private:
  void onInit() override;
  void reconfigure(TaskManagerConfig& config, uint32_t level);
  void onObjects(const biovision_msgs::RecognizedObjectArrayConstPtr& msg);
  void onLtm(const nav_msgs::OccupancyGridConstPtr& msg);
  void onLtmItems(const biovision_msgs::LtmItemArrayConstPtr& msg);
  void onBaseState(const biovision_msgs::AttractorStateConstPtr& msg);
  void onGestureAction(const std_msgs::StringConstPtr& msg);
  void onGoal();
  void onPreempt();
  bool onCancel(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  void onTimeJumpBack();
  void step(const ros::TimerEvent& event);
  Percept perceive(const ros::Time& now);
  void command(const MotorCommand& command, const Percept& percept, const ros::Time& now);
  void finishGoal();
  /// The outcome of the last head/set_mode and base/stop calls, when known (under mutex_).
  void collectServiceAnswers();
  void details(diagnostic_updater::DiagnosticStatusWrapper& status);

  std::mutex mutex_;  // guards everything below against the subscriber, service and action threads
  TaskParameters parameters_;
  std::unique_ptr<TaskManager> manager_;
  std::string map_frame_, base_frame_, camera_frame_;
  double pose_timeout_ = 1.0, seen_hold_ = 1.0, goal_refresh_ = 10.0;

  tf2_ros::Buffer tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  std::deque<Percept::Object> seen_;  ///< recent sightings in map, newest last (bounded)
  OccupancyMap map_;
  std::vector<Percept::Object> remembered_;
  std::string base_behaviour_;
  ros::Time base_state_time_;
  std::string head_mode_;                                     ///< the last mode the head controller accepted
  std::string head_mode_requested_;                           ///< the mode of the head/set_mode call under way
  bool stopped_ = false;                                      ///< base/stop answered for the current stop
  std::string head_mode_answer_, base_stop_answer_;           ///< the last call's outcome, for diagnostics
  bool head_mode_failed_ = false, base_stop_failed_ = false;  ///< the last call was refused or not answered
  ros::WallTime head_mode_retry_at_, base_stop_retry_at_;     ///< no new call before, after a failure
  bool moved_since_stop_call_ = false;          ///< a goal or turn was sent after the base/stop call under way began
  static constexpr double kServiceRetry = 1.0;  ///< [wall s] between a failed service call and the next
  std::string gesture_action_;                  ///< biovision_hri's last hri/action ...
  ros::Time gesture_action_time_;               ///< ... and when it arrived
  bool greeting_ = false;         ///< hri/greet was called for the running greet (hri/stop_greet when it ends)
  std::string greet_answer_;      ///< the last hri/greet or hri/stop_greet outcome, for diagnostics
  ros::WallTime greet_retry_at_;  ///< no new hri/greet call before, after a failed one
  MotorCommand sent_;             ///< the last base command sent (goals are re-sent only when they change)
  ros::Time sent_time_;

  ros::Publisher goal_pub_, bearing_pub_, status_pub_;
  ros::Subscriber objects_sub_, ltm_sub_, items_sub_, base_sub_, gesture_action_sub_;
  std::unique_ptr<biovision_ros_common::AsyncServiceClient<biovision_msgs::SetHeadMode>> head_mode_client_;
  std::unique_ptr<biovision_ros_common::AsyncServiceClient<std_srvs::Trigger>> base_stop_client_;
  std::unique_ptr<biovision_ros_common::AsyncServiceClient<std_srvs::Trigger>> greet_client_, stop_greet_client_;
  ros::ServiceServer cancel_srv_;
  ros::Timer timer_;
  std::unique_ptr<actionlib::SimpleActionServer<biovision_msgs::ExecuteTaskAction>> action_;
  std::set<int> goal_tasks_;  ///< the ids of the action goal's tasks
  ros::Time goal_start_;
  biovision_ros_common::NodeletDiagnostics diagnostics_;
  boost::recursive_mutex reconfigure_mutex_;  // outlives the server
  std::unique_ptr<dynamic_reconfigure::Server<TaskManagerConfig>> reconfigure_server_;
  TaskManagerConfig applied_config_;
};
}  // namespace biovision_tasks
