#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "biovision_common/serial_port.hpp"
#include "phantomx_driver/ax12_joint.hpp"
#include "phantomx_driver/dynamixel_packet.hpp"
#include "phantomx_driver/phantomx_parameters.hpp"

namespace phantomx_driver
{
/// What the driver knows about one servo.
struct ServoState
{
  bool alive = false;        ///< answered the last poll(s)
  bool torque_off = false;   ///< switched off after an overload (stays off until the driver restarts)
  double position = 0.0;     ///< [rad] joint angle (valid once alive)
  double velocity = 0.0;     ///< [rad/s]
  double load = 0.0;         ///< fraction of the maximum torque, signed, [−1, 1]
  double voltage = 0.0;      ///< [V]
  int temperature = 0;       ///< [°C]
  uint8_t error = 0;         ///< the last status error byte (DynamixelError bits)
  unsigned long polls = 0;   ///< answered polls
  unsigned long misses = 0;  ///< unanswered polls since start
  int consecutive_misses = 0;
  int goal_sent = -1;               ///< ticks last written (−1 = none yet, or to be written again)
  unsigned long goal_rewrites = 0;  ///< goals written again: the goal register read back differed (a lost SYNC_WRITE)
  int rewrites_in_a_row = 0;        ///< of the current goal (capped: PanTiltBus::kMaxGoalRewrites)
  double next_retry = 0.0;          ///< when a lost servo is tried again [s]
};

/// Human-readable names of the set error bits ("overload, overheat"); empty for 0.
std::string describeErrorBits(uint8_t error);

/// The pan/tilt pair on one Dynamixel 1.0 bus, driven by step(now): goals to every live servo in one
/// SYNC_WRITE when they change (goal + moving speed, addresses 30–33), then each servo's goal register and
/// present position, speed, load, voltage and temperature by READ 30..43; a goal register that differs from
/// the goal written (a broadcast lost on the line: it gets no reply) has the goal written again; a
/// position or goal above 1023 (a corrupted reply with a good checksum) counts as no answer. A servo that stops answering is "lost" after
/// lost_after polls (the other keeps working) and tried again every retry_period; when it answers again it
/// is re-initialised (speed, torque on). Status error bits are kept; an overload switches that servo's
/// torque off. A serial error closes the port; it is reopened every retry_period. Goals are always within
/// the joint limits and 0–1023. Never throws from step(). Not thread-safe.
class PanTiltBus
{
public:
  static constexpr size_t kPan = 0, kTilt = 1;
  /// A goal whose register reads back different is written again this many times, then left with an error
  /// (a servo whose EEPROM angle limits refuse it would otherwise get a SYNC_WRITE every poll).
  static constexpr int kMaxGoalRewrites = 3;

  /// Throws std::invalid_argument when the parameters do not validate.
  explicit PanTiltBus(const PhantomXParameters& parameters);
  /// Narrows joint `index`'s limits to [lower, upper] ∩ the servo's 300° range (e.g. from the URDF).
  /// Throws std::invalid_argument when lower > upper or they are not finite.
  void setLimits(size_t index, double lower, double upper);
  /// The goal [rad] for joint `index`, clamped into its limits; NaN/inf is ignored (false).
  /// Returns false also when it had to be clamped.
  bool setGoal(size_t index, double rad);
  void step(double now);

  const Ax12Joint& joint(size_t index) const { return joints_.at(index); }
  const ServoState& servo(size_t index) const { return servos_.at(index); }
  bool portOpen() const { return port_.isOpen(); }
  const std::string& lastError() const { return last_error_; }
  unsigned long rejectedPackets() const { return parser_.rejected(); }
  unsigned long portFailures() const { return port_failures_; }

private:
  std::optional<DynamixelPacket> transact(const std::vector<uint8_t>& packet, uint8_t id);
  void poll(size_t index, double now);
  void fail(size_t index, const std::string& why, double now);

  PhantomXParameters p_;
  std::array<Ax12Joint, 2> joints_;
  std::array<ServoState, 2> servos_;
  std::array<int, 2> goal_wanted_{-1, -1};
  int speed_ticks_ = 0;
  biovision_common::SerialPort port_;
  DynamixelPacketParser parser_;
  std::string last_error_;
  double next_port_attempt_ = 0.0;
  unsigned long port_failures_ = 0;
};
}  // namespace phantomx_driver
