#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <biovision_attractor/HeadControllerConfig.h>
#include <biovision_msgs/SalientRegionArray.h>
#include <biovision_msgs/SetHeadMode.h>
#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <nodelet/nodelet.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/JointState.h>

#include <boost/thread/recursive_mutex.hpp>

#include "biovision_attractor/head_attractor.hpp"
#include "biovision_attractor/head_controller_settings.hpp"
#include "biovision_ros_common/nodelet_diagnostics.hpp"

namespace biovision_attractor
{
/// The head controller (thesis §4.7): HeadAttractor turns the head's pan and tilt towards salient regions.
/// Nodelet biovision_attractor/HeadControllerNodelet; the node `head_controller` runs it alone.
///
/// In: `saliency/regions` (biovision_msgs/SalientRegionArray; regions of at least ~min_region_area px^2
/// attract; regions with a NaN/Inf pan, tilt or peak are dropped with an ERROR), `joint_states`
/// (~pan_joint, ~tilt_joint positions [rad]), `camera_info` (optional: the horizontal field of view).
/// Bad input (issue #23): regions with a NaN/Inf or beyond-±pi pan/tilt, messages of more than kMaxRegions
/// regions, joint_states that InputCheck::jointPositions refuses (NaN/Inf/huge, mismatched lengths) and
/// camera_info that InputCheck::cameraInfo refuses (zero size, fx 0/NaN/Inf/tiny) are refused or cut with
/// a throttled error and an ERROR diagnostic; no refused value enters the controller's state.
/// Out: `<pan_joint>/command`, `<tilt_joint>/command` (std_msgs/Float64 [rad], never beyond the URDF's joint
/// limits from `robot_description`), `attractor/head` (biovision_msgs/AttractorState), `/diagnostics`.
/// Service: `head/set_mode` (biovision_msgs/SetHeadMode: explore, track with target "region:<rank>",
/// look_ahead, hold).
///
/// A control loop at ~control_rate in ROS time, not a lazy consumer: it runs whether or not anybody
/// listens. While the pan joint state is older than ~joint_state_timeout it holds: no commands, a throttled
/// warning, a WARN diagnostic. A backward jump of ROS time (looped bag, restarted simulator) resets the
/// attractor's time-based state (HeadAttractor::reset) and waits for a fresh joint state.
/// Settings (HeadControllerSettings) are read once at start; bad ones are fatal (onInit throws). Attractor
/// parameters come through dynamic_reconfigure (cfg/HeadController.cfg): a set that
/// HeadAttractorParameters::validate() rejects keeps the previous one and reports an ERROR diagnostic.
class HeadControllerNodelet : public nodelet::Nodelet
{
public:
  /// Regions looked at per message (the most salient first); a longer message is reported as an ERROR.
  static constexpr size_t kMaxRegions = 256;

  ~HeadControllerNodelet() override;

  /// `base` with every field the reconfigure config names (HeadAttractorParameters::namedDoubles/Bools)
  /// replaced by the config's value. Throws std::logic_error for a config parameter without a field.
  static HeadAttractorParameters parametersFromConfig(const HeadControllerConfig& config, HeadAttractorParameters base);

private:
  void onInit() override;
  void readSettings();
  void readJointLimits();
  void startDiagnostics();
  void reconfigure(HeadControllerConfig& config, uint32_t level);
  void onRegions(const biovision_msgs::SalientRegionArrayConstPtr& msg);
  void onJointStates(const sensor_msgs::JointStateConstPtr& msg);
  void onCameraInfo(const sensor_msgs::CameraInfoConstPtr& msg);
  bool onSetMode(biovision_msgs::SetHeadMode::Request& req, biovision_msgs::SetHeadMode::Response& res);
  void onTimeJumpBack();
  void step(const ros::TimerEvent& event);
  void publishCommands(const HeadAttractor::Output& out);
  void publishState(const HeadAttractor::Output& out, const ros::Time& now);
  void details(diagnostic_updater::DiagnosticStatusWrapper& status);

  HeadControllerSettings settings_;
  HeadAttractorParameters base_;  // the struct's defaults with the URDF's joint limits; configs apply on top

  ros::Publisher pan_pub_, tilt_pub_, state_pub_;
  ros::Subscriber regions_sub_, joints_sub_, info_sub_;
  ros::ServiceServer mode_srv_;
  ros::Timer timer_;
  biovision_ros_common::NodeletDiagnostics diagnostics_;
  boost::recursive_mutex reconfigure_mutex_;  // dynamic_reconfigure::Server takes a boost mutex; outlives it
  std::unique_ptr<dynamic_reconfigure::Server<HeadControllerConfig>> reconfigure_server_;
  HeadControllerConfig applied_config_;  // the last accepted config, restored when one is rejected

  std::mutex mutex_;  // guards everything below
  std::unique_ptr<HeadAttractor> attractor_;
  std::vector<SeenRegion> regions_;                            // the latest frame's, used by one step
  biovision_msgs::SalientRegionArrayConstPtr latest_regions_;  // for set_mode's "region:<rank>"
  double pan_ = 0.0, tilt_ = 0.0, half_fov_ = 0.0;             // [rad]
  ros::Time joints_received_;  // ROS time the pan joint state last arrived; zero = none since start or a time jump
  ros::Time last_step_;        // ROS time of the last control tick; zero = none
  HeadAttractor::Output last_output_;
  unsigned long dropped_regions_ = 0;
  std::atomic<bool> holding_{true};
};
}  // namespace biovision_attractor
