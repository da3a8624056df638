#pragma once

#include <string>

namespace pioneer_driver
{
/// Parameters of the Pioneer 3DX driver. Defaults: the P3DX rows of the p2os robot parameter tables
/// (p3dx_sh_params) and p2os's speed limits; timings from the ARCOS watchdog (2 s) and RosAria (0.6 s).
struct PioneerParameters
{
  std::string port = "/dev/ttyUSB0";  ///< serial device (or a pty of pioneer_emulator)
  int baud = 9600;                    ///< host port speed [bit/s]: 9600 (ARCOS default), 19200, 38400, 57600, 115200
  double max_linear_speed = 0.5;      ///< |VEL| cap [m/s], (0, 2.2] (p2os max_xspeed 0.5; P3DX MaxVelocity 2.2)
  double max_angular_speed = 1.745;  ///< |RVEL| cap [rad/s], (0, 8.7] (p2os max_yawspeed 100°/s; MaxRVelocity 500°/s)
  double cmd_vel_timeout = 0.5;      ///< [s] without cmd_vel the speed is set to zero, [0.05, 2]
  double pulse_period =
      1.0;  ///< [s] the setpoint is sent again after this long without a command (keep-alive, a lost stop repeated), [0.05, 1.9] (ARCOS stops after 2 s of silence)
  double sip_timeout = 1.0;             ///< [s] no valid SIP for this long = link lost, [0.3, 10] (SIPs every 0.1 s)
  double reconnect_period = 1.0;        ///< [s] between connection attempts, [0.1, 60]
  double sync_timeout = 0.5;            ///< [s] wait for each SYNC echo, [0.05, 5]
  bool enable_motors = true;            ///< send ENABLE 1 after OPEN (the motors are off after connecting)
  double angle_conv_factor = 0.001534;  ///< THPOS unit [rad], (0, 0.1] (2π/4096)
  double dist_conv_factor = 1.0;        ///< XPOS/YPOS unit [mm], (0, 10]
  double vel_conv_factor = 1.0;         ///< LVEL/RVEL unit [mm/s], (0, 10]
  double diff_conv_factor = 0.0056;     ///< ω = (RVEL − LVEL)/2 · this [rad/s per mm/s], (0, 1]
  std::string odom_frame = "odom";
  std::string base_frame = "base_link";
  bool publish_tf = true;  ///< broadcast odom → base_link

  /// Throws std::invalid_argument naming the field and its range.
  void validate() const;
};

/// Calls `read(name, field)` for every parameter, in the order of the README and config/pioneer_driver.yaml:
/// the node reads ROS parameters and the parameter-file test reads the YAML through the same list.
template <typename Read>
void visitParameters(PioneerParameters& p, Read&& read)
{
  read("port", p.port);
  read("baud", p.baud);
  read("max_linear_speed", p.max_linear_speed);
  read("max_angular_speed", p.max_angular_speed);
  read("cmd_vel_timeout", p.cmd_vel_timeout);
  read("pulse_period", p.pulse_period);
  read("sip_timeout", p.sip_timeout);
  read("reconnect_period", p.reconnect_period);
  read("sync_timeout", p.sync_timeout);
  read("enable_motors", p.enable_motors);
  read("angle_conv_factor", p.angle_conv_factor);
  read("dist_conv_factor", p.dist_conv_factor);
  read("vel_conv_factor", p.vel_conv_factor);
  read("diff_conv_factor", p.diff_conv_factor);
  read("odom_frame", p.odom_frame);
  read("base_frame", p.base_frame);
  read("publish_tf", p.publish_tf);
}
}  // namespace pioneer_driver
