#pragma once

#include <array>
#include <atomic>
#include <memory>
#include <mutex>
#include <thread>

#include <nodelet/nodelet.h>
#include <ros/ros.h>
#include <std_msgs/Float64.h>

#include "biovision_ros_common/nodelet_diagnostics.hpp"
#include "phantomx_driver/pan_tilt_bus.hpp"

namespace phantomx_driver
{
/// The PhantomX pan/tilt driver as a nodelet: `head_pan_joint/command` and `head_tilt_joint/command`
/// (std_msgs/Float64 [rad], as the simulator takes them) → PanTiltBus goals, clamped to the URDF limits of
/// robot_description; the bus is polled on its own thread at ~poll_rate → `joint_states` (the servos that
/// answer); `diagnostics` ERROR while a servo is lost, overloaded or the port is down. Not lazy.
class PhantomXDriverNodelet : public nodelet::Nodelet
{
public:
  ~PhantomXDriverNodelet() override;

private:
  void onInit() override;
  void run();
  void onCommand(size_t index, const std_msgs::Float64ConstPtr& msg);

  PhantomXParameters parameters_;
  std::unique_ptr<PanTiltBus> bus_;
  std::array<ros::Subscriber, 2> command_subs_;
  ros::Publisher joint_pub_;
  biovision_ros_common::NodeletDiagnostics diagnostics_;
  std::mutex mutex_;  // goals_ and the diagnostics' copy of the bus state
  std::array<double, 2> goals_{NAN, NAN};
  std::array<bool, 2> goal_new_{false, false};
  std::array<ServoState, 2> states_;
  bool port_open_ = false;
  std::string last_error_;
  unsigned long rejected_ = 0;
  std::atomic<bool> running_{false};
  std::thread thread_;
};
}  // namespace phantomx_driver
