#pragma once

#include <cstdint>
#include <string>

namespace phantomx_driver
{
/// One AX-12A joint: how radians map onto goal/present positions and which goals are allowed.
/// ticks = 512 + direction · (rad + offset) / kRadPerTick, 0–1023 over 300° (0.29°/tick).
struct Ax12Joint
{
  static constexpr double kRadPerTick = 300.0 / 1023.0 * 3.14159265358979323846 / 180.0;  ///< ≈ 0.005118
  static constexpr int kCenter = 512;

  std::string name;     ///< URDF joint name (joint_states, limits)
  uint8_t id = 1;       ///< Dynamixel ID on the bus
  double offset = 0.0;  ///< [rad] added to the joint angle before conversion (mounting offset)
  int direction = 1;    ///< +1 or −1: servo sense relative to the URDF axis
  double lower = -1.5;  ///< [rad] joint limit (the URDF's, narrowed by the servo's 0–1023 range)
  double upper = 1.5;   ///< [rad]

  /// The goal position for `rad`, first clamped into [lower, upper], then into 0–1023, rounded to the
  /// nearest tick that is not beyond a limit (when one exists). NaN → the
  /// current goal is kept by the caller (returns −1).
  int goalTicks(double rad) const;
  /// The joint angle [rad] of a present position.
  double radians(int ticks) const;
  /// Whether `rad` is within the limits (with a half-tick tolerance).
  bool withinLimits(double rad) const;
};

/// AX-12 moving speed register value for `rad_per_s` (0.111 rpm per unit), in [1, 1023]: never 0, which
/// means "maximum, uncontrolled".
int movingSpeedTicks(double rad_per_s);
/// Present speed register (bit 10 = direction) → rad/s, signed.
double presentSpeedRadPerS(int value);
}  // namespace phantomx_driver
