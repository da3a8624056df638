#pragma once

#include <string>
#include <vector>

#include "biovision_common/serial_port.hpp"
#include "pioneer_driver/arcos_packet.hpp"
#include "pioneer_driver/pioneer_odometry.hpp"
#include "pioneer_driver/pioneer_parameters.hpp"
#include "pioneer_driver/standard_sip.hpp"

namespace pioneer_driver
{
/// What the connection knows about itself, for diagnostics.
struct PioneerStatus
{
  bool connected = false;
  std::string robot_name, robot_class, robot_subclass;  ///< from the SYNC2 reply
  std::string last_error;                               ///< why the last attempt failed or the link was lost
  unsigned long connects = 0;                           ///< sessions opened
  unsigned long losses = 0;                             ///< sessions lost (serial error, SIP time-out)
  unsigned long sips = 0;                               ///< valid standard SIPs
  unsigned long rejected_packets = 0;                   ///< bad checksums or malformed SIPs since start
  ArcosVelocity commanded;                              ///< the setpoint last sent
  bool watchdog_stopped = false;                        ///< the cmd_vel time-out holds the base at zero
};

/// The ARCOS session with a Pioneer controller over a serial port, as a state machine driven by
/// spinOnce(now): connect (SYNC0/1/2 with the robot's name, OPEN, PULSE, ENABLE), then each step read SIPs,
/// send VEL + RVEL when the setpoint changes and again after every pulse_period without a command (a lost
/// stop is repeated), zero it when no command came for cmd_vel_timeout; a SYNC2 reply without the robot's
/// name is refused (an echoing port); a serial error or no SIP for sip_timeout sends VEL 0, RVEL 0, CLOSE
/// (the robot stops even when only its replies are lost), closes the port and retries every
/// reconnect_period. Never throws from spinOnce: failures are in status(). Times are seconds of a
/// monotonic clock chosen by the caller. Not thread-safe.
class PioneerConnection
{
public:
  /// Throws std::invalid_argument when the parameters do not validate.
  explicit PioneerConnection(const PioneerParameters& parameters);
  /// Sends VEL 0, RVEL 0 and CLOSE when connected.
  ~PioneerConnection();
  PioneerConnection(const PioneerConnection&) = delete;
  PioneerConnection& operator=(const PioneerConnection&) = delete;

  /// New speed caps and cmd_vel time-out (dynamic_reconfigure) from `parameters`; the other fields are
  /// ignored (they need a new session). Throws std::invalid_argument (and keeps the old values) when
  /// `parameters` do not validate. The next step re-clamps the command in force.
  void setMotionLimits(const PioneerParameters& parameters);
  /// The latest velocity command [m/s, rad/s] received at `now`; clamped when sent.
  void setCommand(double linear_m_s, double angular_rad_s, double now);
  /// One step: (re)connects when due, reads for up to `read_timeout` s, sends what is due. Returns the
  /// standard SIPs that arrived, in order. The handshake blocks for up to 3 × sync_timeout per SYNC.
  std::vector<StandardSip> spinOnce(double now, double read_timeout);
  /// Stops the base and closes the session (the next spinOnce reconnects after reconnect_period).
  void disconnect(const std::string& why, double now);
  const PioneerStatus& status() const { return status_; }
  const PioneerParameters& parameters() const { return p_; }

private:
  void connect(double now);
  std::vector<uint8_t> awaitPacket(double timeout);
  void send(const std::vector<uint8_t>& packet, double now);
  void lose(const std::string& why, double now);

  PioneerParameters p_;
  biovision_common::SerialPort port_;
  ArcosPacketParser parser_;
  PioneerStatus status_;
  double next_attempt_ = 0.0;
  double last_sip_ = 0.0, last_tx_ = 0.0;
  double command_time_ = -1e9;
  double command_v_ = 0.0, command_w_ = 0.0;
  unsigned long rejected_base_ = 0;
};
}  // namespace pioneer_driver
