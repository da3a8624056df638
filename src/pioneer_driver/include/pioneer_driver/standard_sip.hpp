#pragma once

#include <cstdint>
#include <vector>

namespace pioneer_driver
{
/// One ARCOS standard server information packet (SIP), raw fields as the controller sends them
/// (Pioneer 3 Operations Manual Table 4; p2os sip.cpp ParseStandard). Sent every 100 ms once open.
struct StandardSip
{
  bool moving = false;        ///< type 0x33 (moving) rather than 0x32 (stopped)
  uint16_t xpos = 0;          ///< [mm · DistConvFactor], 15 least significant bits (wraps at 32768)
  uint16_t ypos = 0;          ///< [mm · DistConvFactor], 15 least significant bits
  int16_t thpos = 0;          ///< heading [AngleConvFactor rad units, 4096 per turn]
  int16_t left_velocity = 0;  ///< [mm/s · VelConvFactor]
  int16_t right_velocity = 0;
  uint8_t battery = 0;         ///< [0.1 V]
  uint16_t stall_bumpers = 0;  ///< bit 0 left stall, bits 1–7 front bumpers, bit 8 right stall, bits 9–15 rear
  int16_t control = 0;         ///< heading setpoint
  uint16_t flags = 0;          ///< bit 0 motors enabled, bits 1–4 sonar arrays
  uint8_t compass = 0;         ///< [2°]
  std::vector<std::pair<uint8_t, uint16_t>> sonars;  ///< (number, range [mm]) of the sonars updated

  bool leftStall() const { return (stall_bumpers & 0x0001) != 0; }
  bool rightStall() const { return (stall_bumpers & 0x0100) != 0; }
  uint8_t frontBumpers() const { return static_cast<uint8_t>((stall_bumpers >> 1) & 0x7F); }
  uint8_t rearBumpers() const { return static_cast<uint8_t>((stall_bumpers >> 9) & 0x7F); }
  bool motorsEnabled() const { return (flags & 0x0001) != 0; }
  double batteryVolts() const { return battery * 0.1; }
};

/// True for the DATA of a standard SIP (type byte 0x32 or 0x33).
inline bool isStandardSip(const std::vector<uint8_t>& data)
{
  return !data.empty() && (data[0] == 0x32 || data[0] == 0x33);
}

/// Parses the DATA of a standard SIP (type byte first). Throws std::invalid_argument when it is not one
/// or is shorter than its fixed part (20 bytes) or its sonar list.
StandardSip parseStandardSip(const std::vector<uint8_t>& data);
/// The DATA bytes of `sip` (the inverse of parseStandardSip, plus zeroed TIMER/ANALOG/DIGIN/DIGOUT), used
/// by the emulator.
std::vector<uint8_t> encodeStandardSip(const StandardSip& sip);
}  // namespace pioneer_driver
