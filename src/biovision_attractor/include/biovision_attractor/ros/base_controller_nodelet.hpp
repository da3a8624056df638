#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <biovision_attractor/BaseControllerConfig.h>
#include <biovision_msgs/EgoMap.h>
#include <biovision_msgs/PioneerState.h>
#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <nodelet/nodelet.h>
#include <ros/ros.h>
#include <std_msgs/Float64.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <boost/thread/recursive_mutex.hpp>

#include "biovision_attractor/base_attractor.hpp"
#include "biovision_attractor/base_controller_settings.hpp"
#include "biovision_ros_common/nodelet_diagnostics.hpp"

namespace biovision_attractor
{
/// The base controller (thesis §5.4, issue 16): BaseAttractor steers the base to a goal around the
/// obstacles of the short-term memory. Nodelet biovision_attractor/BaseControllerNodelet; the node
/// `base_controller` runs it alone. A control loop at ~control_rate in ROS time (not lazy: it must stop the
/// base whether or not anybody listens).
///
/// In: `memory/stm` (biovision_msgs/EgoMap, base_link sectors; a map with a NaN angle or distance, unequal
/// array lengths or a stamp in the future is rejected with an ERROR), `odom` (nav_msgs/Odometry in
/// ~odom_frame), `goal` (geometry_msgs/PoseStamped in any frame tf can transform into ~odom_frame at the
/// latest time; a NaN, a goal farther than ~max_goal_distance or a missing transform is refused with an
/// ERROR and stops the base), `goal_bearing` (std_msgs/Float64 [rad, base_link, + = left]: drive on that
/// odometry heading until stopped), optional `pioneer_state` (biovision_msgs/PioneerState from
/// pioneer_driver: a pressed bumper or a stalled wheel stops the base and clears the goal).
/// Out: `cmd_vel` (geometry_msgs/Twist, never beyond max_linear/max_angular, never NaN), `attractor/base`
/// (biovision_msgs/AttractorState: behaviour idle | goal | blocked | trapped | reached | hold | watchdog |
/// bumper | stall; per sector the repeller angle, strength lambda_i (repulsion) and forcelet; the goal's attraction
/// in its sector; rate; target = goal bearing), `/diagnostics`.
/// Services: `base/stop` (std_srvs/Trigger: zero and forget the goal), `base/hold` (std_srvs/SetBool: true
/// = zero and keep the goal, false = resume).
/// Watchdog: while a goal is active and the STM or the odometry is older than ~stm_timeout / ~odom_timeout
/// (by receipt or by stamp), cmd_vel is zero (a WARN diagnostic). A backward jump of ROS time resets the
/// attractor and waits for fresh STM and odometry.
class BaseControllerNodelet : public nodelet::Nodelet
{
public:
  ~BaseControllerNodelet() override;

private:
  struct Pose
  {
    double x = 0, y = 0, yaw = 0;
  };
  enum class Mode
  {
    kIdle,     // no goal
    kPose,     // goal position in odom_frame
    kBearing,  // odometry heading to keep
  };

  void onInit() override;
  void readSettings();
  void startDiagnostics();
  void reconfigure(BaseControllerConfig& config, uint32_t level);
  void onStm(const biovision_msgs::EgoMapConstPtr& msg);
  void onOdom(const nav_msgs::OdometryConstPtr& msg);
  void onGoal(const geometry_msgs::PoseStampedConstPtr& msg);
  void onGoalBearing(const std_msgs::Float64ConstPtr& msg);
  void onPioneerState(const biovision_msgs::PioneerStateConstPtr& msg);
  bool onStop(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool onHold(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res);
  void onTimeJumpBack();
  void step(const ros::TimerEvent& event);
  void publishZero();
  void publishState(const BaseAttractor::Output& out, const std::string& behaviour, double goal_bearing,
                    const ros::Time& now);
  void refuseGoal(const std::string& why);
  void details(diagnostic_updater::DiagnosticStatusWrapper& status);

  BaseControllerSettings settings_;
  ros::Publisher cmd_pub_, state_pub_;
  ros::Subscriber stm_sub_, odom_sub_, goal_sub_, bearing_sub_, pioneer_sub_;
  ros::ServiceServer stop_srv_, hold_srv_;
  ros::Timer timer_;
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  biovision_ros_common::NodeletDiagnostics diagnostics_;
  boost::recursive_mutex reconfigure_mutex_;  // dynamic_reconfigure::Server takes a boost mutex; outlives it
  std::unique_ptr<dynamic_reconfigure::Server<BaseControllerConfig>> reconfigure_server_;
  BaseControllerConfig applied_config_;

  std::mutex mutex_;  // guards everything below
  std::unique_ptr<BaseAttractor> attractor_;
  std::vector<BaseAttractor::Sector> stm_;
  ros::Time stm_received_, stm_stamp_;    // zero = none since start or a time jump
  ros::Time odom_received_, odom_stamp_;  // zero = none
  Pose pose_;
  Mode mode_ = Mode::kIdle;
  double goal_x_ = 0, goal_y_ = 0, goal_heading_ = 0;
  bool hold_ = false;
  std::string stopped_by_;  // "bumper" or "stall" while the driver reports one
  ros::Time last_step_;
  std::string behaviour_ = "idle";
  BaseAttractor::Output last_output_;
  unsigned long watchdog_stops_ = 0, rejected_stm_ = 0, refused_goals_ = 0;
  bool zero_sent_ = false;  // idle: one zero command after the goal ended
};
}  // namespace biovision_attractor
