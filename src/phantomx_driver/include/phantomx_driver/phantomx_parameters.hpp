#pragma once

#include <string>

namespace phantomx_driver
{
/// Parameters of the PhantomX pan/tilt driver (two AX-12A on one Dynamixel 1.0 bus, directly or through
/// an ArbotiX board in pass-through). Defaults: the AX-12A factory settings (1 Mbps; IDs 1 and 2 as the
/// PhantomX kit assigns them) and the simulator's servo speed (3 rad/s).
struct PhantomXParameters
{
  std::string port = "/dev/ttyUSB1";  ///< serial device (USB2Dynamixel, ArbotiX) or a pty of phantomx_emulator
  int baud = 1000000;                 ///< [bit/s]: 57600, 115200, 500000, 1000000
  std::string pan_joint = "head_pan_joint";
  std::string tilt_joint = "head_tilt_joint";
  int pan_id = 1;                      ///< Dynamixel ID, [0, 253]
  int tilt_id = 2;                     ///< [0, 253], ≠ pan_id
  double pan_offset = 0.0;             ///< [rad] mounting offset, [−0.5, 0.5]
  double tilt_offset = 0.0;            ///< [rad], [−0.5, 0.5]
  int pan_direction = 1;               ///< +1 or −1
  int tilt_direction = 1;              ///< +1 or −1
  double pan_lower = -1.5708;          ///< [rad] used when robot_description has no limit; the URDF's otherwise
  double pan_upper = 1.5708;           ///< [rad]
  double tilt_lower = -0.7854;         ///< [rad]
  double tilt_upper = 0.7854;          ///< [rad]
  double max_speed = 3.0;              ///< moving speed [rad/s], (0, 6.17] (AX-12A no-load 59 rpm)
  double poll_rate = 50.0;             ///< joint_states rate [Hz], [30, 200]
  double response_timeout = 0.02;      ///< [s] wait for a status packet, [0.002, 0.5]
  int lost_after = 3;                  ///< consecutive unanswered polls before a servo is "lost", [1, 100]
  double retry_period = 1.0;           ///< [s] between attempts to reach a lost servo or reopen the port, [0.1, 60]
  bool torque_off_on_overload = true;  ///< switch a servo's torque off when it reports overload

  /// Throws std::invalid_argument naming the field and its range.
  void validate() const;
};

/// Calls `read(name, field)` for every parameter (the node reads ROS parameters, the parameter-file test
/// reads config/phantomx_driver.yaml through the same list).
template <typename Read>
void visitParameters(PhantomXParameters& p, Read&& read)
{
  read("port", p.port);
  read("baud", p.baud);
  read("pan_joint", p.pan_joint);
  read("tilt_joint", p.tilt_joint);
  read("pan_id", p.pan_id);
  read("tilt_id", p.tilt_id);
  read("pan_offset", p.pan_offset);
  read("tilt_offset", p.tilt_offset);
  read("pan_direction", p.pan_direction);
  read("tilt_direction", p.tilt_direction);
  read("pan_lower", p.pan_lower);
  read("pan_upper", p.pan_upper);
  read("tilt_lower", p.tilt_lower);
  read("tilt_upper", p.tilt_upper);
  read("max_speed", p.max_speed);
  read("poll_rate", p.poll_rate);
  read("response_timeout", p.response_timeout);
  read("lost_after", p.lost_after);
  read("retry_period", p.retry_period);
  read("torque_off_on_overload", p.torque_off_on_overload);
}
}  // namespace phantomx_driver
