#include "pioneer_driver/ros/pioneer_driver_nodelet.hpp"

#include <biovision_msgs/PioneerState.h>
#include <nav_msgs/Odometry.h>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/BatteryState.h>
#include <tf2/LinearMath/Quaternion.h>

#include "biovision_common/steady_seconds.hpp"
#include "biovision_ros_common/typed_parameter.hpp"
#include "pioneer_driver/ros/pioneer_driver_config.hpp"

namespace pioneer_driver
{
PioneerDriverNodelet::~PioneerDriverNodelet()
{
  running_ = false;
  if (thread_.joinable())
    thread_.join();
  connection_.reset();  // stops the base and closes the session
}

void PioneerDriverNodelet::onInit()
{
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  try
  {
    // A value of the wrong type is refused, not replaced by the default (a driver told `_port:=123` opened
    // /dev/ttyUSB0).
    visitParameters(parameters_, [&](const std::string& name, auto& value) {
      biovision_ros_common::readTypedParameter(pnh, name, value);
    });
    connection_ = std::make_unique<PioneerConnection>(parameters_);
  }
  catch (const std::invalid_argument& e)
  {
    NODELET_FATAL("%s", e.what());
    throw;
  }
  odometry_ = PioneerOdometry(parameters_);
  odom_pub_ = nh.advertise<nav_msgs::Odometry>("odom", 10);
  battery_pub_ = nh.advertise<sensor_msgs::BatteryState>("battery_state", 1);
  state_pub_ = nh.advertise<biovision_msgs::PioneerState>("pioneer_state", 10);
  if (parameters_.publish_tf)
    tf_ = std::make_unique<tf2_ros::TransformBroadcaster>();
  biovision_ros_common::DiagnosticsOptions options;
  options.status_name = "Pioneer base";
  options.rate_topic = "odom";
  options.default_max_rate = 15.0;
  options.working_message = "connected";
  options.details = [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
    std::lock_guard<std::mutex> lock(status_mutex_);
    if (!status_.connected)
      s.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "disconnected: " + status_.last_error);
    s.add("port", parameters_.port);
    s.add("connected", status_.connected);
    s.add("robot", status_.robot_name + " " + status_.robot_class + " " + status_.robot_subclass);
    s.add("sessions opened", status_.connects);
    s.add("sessions lost", status_.losses);
    s.add("SIPs", status_.sips);
    s.add("rejected packets", status_.rejected_packets);
    s.add("implausible SIPs refused", implausible_sips_.load());
    s.add("VEL [mm/s]", status_.commanded.vel_mm_s);
    s.add("RVEL [deg/s]", status_.commanded.rvel_deg_s);
    s.add("cmd_vel time-out stop", status_.watchdog_stopped);
    s.add("last error", status_.last_error);
  };
  diagnostics_.init(nh, pnh, getName(), options);
  // The speed caps and time-out are reconfigurable; the server reads their start values from ~.
  reconfigure_server_ = std::make_unique<dynamic_reconfigure::Server<PioneerDriverConfig>>(reconfigure_mutex_, pnh);
  reconfigure_server_->setCallback([this](PioneerDriverConfig& c, uint32_t level) { reconfigure(c, level); });
  cmd_sub_ = nh.subscribe("cmd_vel", 10, &PioneerDriverNodelet::onCommand, this);
  running_ = true;
  thread_ = std::thread([this] { run(); });
  NODELET_INFO("Pioneer driver on %s at %d bit/s (caps %.2f m/s, %.2f rad/s, cmd_vel time-out %.2f s)",
               parameters_.port.c_str(), parameters_.baud, parameters_.max_linear_speed, parameters_.max_angular_speed,
               parameters_.cmd_vel_timeout);
}

void PioneerDriverNodelet::reconfigure(PioneerDriverConfig& config, uint32_t /*level*/)
{
  const PioneerParameters next = withConfig(parameters_, config);
  try
  {
    next.validate();
  }
  catch (const std::invalid_argument& e)
  {
    diagnostics_.health().reportError(getName(), std::string("reconfigure refused: ") + e.what());
    config.max_linear_speed = parameters_.max_linear_speed;
    config.max_angular_speed = parameters_.max_angular_speed;
    config.cmd_vel_timeout = parameters_.cmd_vel_timeout;
    return;
  }
  parameters_.max_linear_speed = next.max_linear_speed;  // for the next refusal's fallback
  parameters_.max_angular_speed = next.max_angular_speed;
  parameters_.cmd_vel_timeout = next.cmd_vel_timeout;
  std::lock_guard<std::mutex> lock(command_mutex_);
  pending_limits_ = std::make_unique<PioneerParameters>(next);
}

void PioneerDriverNodelet::onCommand(const geometry_msgs::TwistConstPtr& msg)
{
  if (!std::isfinite(msg->linear.x) || !std::isfinite(msg->angular.z))
    diagnostics_.health().reportError(getName(), "cmd_vel with NaN or infinity: the base is stopped");
  std::lock_guard<std::mutex> lock(command_mutex_);
  command_v_ = msg->linear.x;
  command_w_ = msg->angular.z;
  command_time_ = biovision_common::steadySeconds();
  command_new_ = true;
}

void PioneerDriverNodelet::run()
{
  unsigned long connects = 0, losses = 0, rejected = 0;
  std::string last_error;
  while (running_ && ros::ok())
  {
    {
      std::lock_guard<std::mutex> lock(command_mutex_);
      if (pending_limits_)
      {
        connection_->setMotionLimits(*pending_limits_);  // validated by reconfigure()
        NODELET_INFO("caps %.2f m/s, %.2f rad/s, cmd_vel time-out %.2f s", pending_limits_->max_linear_speed,
                     pending_limits_->max_angular_speed, pending_limits_->cmd_vel_timeout);
        pending_limits_.reset();
      }
      if (command_new_)
        connection_->setCommand(command_v_, command_w_, command_time_);
      command_new_ = false;
    }
    const auto sips = connection_->spinOnce(biovision_common::steadySeconds(), 0.02);
    const PioneerStatus& st = connection_->status();
    if (st.connects != connects)
    {
      connects = st.connects;
      odometry_.restartCounters();  // the controller restarts its counters with each session; the pose goes on
      NODELET_INFO("connected to %s %s %s on %s", st.robot_name.c_str(), st.robot_class.c_str(),
                   st.robot_subclass.c_str(), parameters_.port.c_str());
    }
    if (st.losses != losses || (!st.connected && st.last_error != last_error))
      diagnostics_.health().reportError(getName(), "Pioneer link down, base stopped: " + st.last_error);
    if (st.rejected_packets != rejected)
      diagnostics_.health().reportError(getName(), std::to_string(st.rejected_packets) +
                                                       " packets rejected (bad checksum or malformed SIP)");
    losses = st.losses;
    rejected = st.rejected_packets;
    last_error = st.last_error;
    {
      std::lock_guard<std::mutex> lock(status_mutex_);
      status_ = st;
    }
    for (const auto& sip : sips)
      publish(sip);
    implausible_sips_ = odometry_.implausible();
  }
}

void PioneerDriverNodelet::publish(const StandardSip& sip)
{
  if (!odometry_.update(sip, biovision_common::steadySeconds()))
  {
    diagnostics_.health().reportError(getName(), "an implausible SIP was refused (a wheel beyond " +
                                                     std::to_string(PioneerOdometry::kMaxWheelSpeed) +
                                                     " m/s, or a jump or turn no P3-DX makes in the time since the "
                                                     "last SIP): odometry unchanged");
    return;
  }
  const ros::Time stamp = ros::Time::now();
  if (stamp.isZero())
  {
    // use_sim_time without a /clock yet: a zero stamp would be taken for "no time" downstream.
    // Throttled on the steady clock: ROS time is what is missing (a ROS-time throttle never fires at 0).
    if (biovision_common::steadySeconds() - last_no_time_warning_ >= 5.0)
    {
      NODELET_WARN("no ROS time yet (use_sim_time without /clock?): odometry not published");
      last_no_time_warning_ = biovision_common::steadySeconds();
    }
    return;
  }
  tf2::Quaternion q;
  q.setRPY(0.0, 0.0, odometry_.yaw());
  nav_msgs::Odometry odom;
  odom.header.stamp = stamp;
  odom.header.frame_id = parameters_.odom_frame;
  odom.child_frame_id = parameters_.base_frame;
  odom.pose.pose.position.x = odometry_.x();
  odom.pose.pose.position.y = odometry_.y();
  odom.pose.pose.orientation.x = q.x();
  odom.pose.pose.orientation.y = q.y();
  odom.pose.pose.orientation.z = q.z();
  odom.pose.pose.orientation.w = q.w();
  odom.twist.twist.linear.x = odometry_.linearVelocity();
  odom.twist.twist.angular.z = odometry_.angularVelocity();
  // Wheel odometry: good in x, y, yaw for short runs; z, roll, pitch unobserved (large).
  for (int i : {0, 7})
    odom.pose.covariance[i] = 1e-3;
  for (int i : {14, 21, 28})
    odom.pose.covariance[i] = 1e6;
  odom.pose.covariance[35] = 1e-2;
  odom_pub_.publish(odom);
  diagnostics_.tick();
  if (tf_)
  {
    geometry_msgs::TransformStamped t;
    t.header = odom.header;
    t.child_frame_id = odom.child_frame_id;
    t.transform.translation.x = odometry_.x();
    t.transform.translation.y = odometry_.y();
    t.transform.rotation = odom.pose.pose.orientation;
    tf_->sendTransform(t);
  }
  sensor_msgs::BatteryState battery;
  battery.header.stamp = stamp;
  battery.voltage = static_cast<float>(sip.batteryVolts());
  battery.current = battery.charge = battery.capacity = battery.design_capacity = battery.percentage = NAN;
  battery.power_supply_status = sensor_msgs::BatteryState::POWER_SUPPLY_STATUS_UNKNOWN;
  battery.power_supply_health = sensor_msgs::BatteryState::POWER_SUPPLY_HEALTH_UNKNOWN;
  battery.power_supply_technology = sensor_msgs::BatteryState::POWER_SUPPLY_TECHNOLOGY_UNKNOWN;
  battery.present = true;
  battery_pub_.publish(battery);
  biovision_msgs::PioneerState state;
  state.header.stamp = stamp;
  state.header.frame_id = parameters_.base_frame;
  state.connected = connection_->status().connected;
  state.motors_enabled = sip.motorsEnabled();
  state.left_stall = sip.leftStall();
  state.right_stall = sip.rightStall();
  state.front_bumpers = sip.frontBumpers();
  state.rear_bumpers = sip.rearBumpers();
  state.battery_voltage = battery.voltage;
  state.commanded_linear = static_cast<float>(connection_->status().commanded.vel_mm_s * 1e-3);
  state.commanded_angular = static_cast<float>(connection_->status().commanded.rvel_deg_s * M_PI / 180.0);
  state_pub_.publish(state);
}
}  // namespace pioneer_driver

PLUGINLIB_EXPORT_CLASS(pioneer_driver::PioneerDriverNodelet, nodelet::Nodelet)
