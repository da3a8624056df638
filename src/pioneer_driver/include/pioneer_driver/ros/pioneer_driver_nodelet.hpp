#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <thread>

#include <boost/thread/recursive_mutex.hpp>
#include <dynamic_reconfigure/server.h>
#include <geometry_msgs/Twist.h>
#include <nodelet/nodelet.h>
#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include "biovision_ros_common/nodelet_diagnostics.hpp"
#include "pioneer_driver/PioneerDriverConfig.h"
#include "pioneer_driver/pioneer_connection.hpp"
#include "pioneer_driver/pioneer_odometry.hpp"

namespace pioneer_driver
{
/// The Pioneer 3DX base driver as a nodelet: `cmd_vel` → PioneerConnection (VEL/RVEL clamped, 0.5 s
/// time-out, PULSE, reconnect) on its own thread; each standard SIP → `odom` (+ tf odom → base_link),
/// `battery_state`, `pioneer_state` (stall, bumpers, motors); `diagnostics` ERROR while the link is down
/// or after rejected packets. Not lazy: a driver runs whether or not anyone listens.
class PioneerDriverNodelet : public nodelet::Nodelet
{
public:
  ~PioneerDriverNodelet() override;

private:
  void onInit() override;
  void run();
  void onCommand(const geometry_msgs::TwistConstPtr& msg);
  void publish(const StandardSip& sip);
  void reconfigure(PioneerDriverConfig& config, uint32_t level);

  PioneerParameters parameters_;
  std::unique_ptr<PioneerConnection> connection_;
  PioneerOdometry odometry_;  // the run() thread's
  std::atomic<unsigned long> implausible_sips_{0};
  double last_no_time_warning_ = -1e9;  // steady clock [s]  // odometry_.implausible(), for the diagnostics thread
  ros::Subscriber cmd_sub_;
  ros::Publisher odom_pub_, battery_pub_, state_pub_;
  std::unique_ptr<tf2_ros::TransformBroadcaster> tf_;
  biovision_ros_common::NodeletDiagnostics diagnostics_;
  std::mutex command_mutex_;
  double command_v_ = 0.0, command_w_ = 0.0, command_time_ = -1e9;
  bool command_new_ = false;
  std::unique_ptr<PioneerParameters> pending_limits_;  // from reconfigure, applied by the driver thread
  boost::recursive_mutex reconfigure_mutex_;           // outlives the server (declared before it)
  std::unique_ptr<dynamic_reconfigure::Server<PioneerDriverConfig>> reconfigure_server_;
  std::mutex status_mutex_;
  PioneerStatus status_;  // a copy for the diagnostics thread
  std::atomic<bool> running_{false};
  std::thread thread_;
};
}  // namespace pioneer_driver
