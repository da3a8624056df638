#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pioneer_driver
{
/// ARCOS client command numbers (Pioneer 3 Operations Manual command table; p2os robot_params.hpp).
enum ArcosCommand : uint8_t
{
  kSync0 = 0,  ///< also PULSE once a session is open
  kSync1 = 1,  ///< also OPEN
  kSync2 = 2,  ///< also CLOSE
  kPulse = 0,
  kOpen = 1,
  kClose = 2,
  kEnable = 4,  ///< int 1/0: motors on/off (off after connecting)
  kSetV = 6,    ///< max translation speed [mm/s]
  kSetRv = 10,  ///< max rotation speed [deg/s]
  kVel = 11,    ///< translation setpoint [mm/s], signed
  kRvel = 21,   ///< rotation setpoint [deg/s], signed
  kSonar = 28,
  kStop = 29,
  kEStop = 55,
};

/// Argument type bytes of ARCOS commands.
enum ArcosArgType : uint8_t
{
  kArgPositive = 0x3B,  ///< positive int: LSB, MSB
  kArgNegative = 0x1B,  ///< negative int: absolute value LSB, MSB
  kArgString = 0x2B,    ///< length byte, then the characters
};

constexpr uint8_t kHeader0 = 0xFA;
constexpr uint8_t kHeader1 = 0xFB;
/// Largest COUNT byte accepted (p2os refuses packets over ~200 bytes).
constexpr size_t kMaxCount = 200;

/// ARCOS checksum of a packet's DATA bytes (not the header, not the count): the sum of big-endian 16-bit
/// pairs modulo 2^16, and with an odd count the last byte XOR-ed into the low byte. Sent high byte first.
/// Worked values: {0x00} → 0x0000 (SYNC0), {0x04,0x3B,0x01,0x00} → 0x053B (ENABLE 1).
uint16_t arcosChecksum(const uint8_t* data, size_t size);
inline uint16_t arcosChecksum(const std::vector<uint8_t>& data)
{
  return arcosChecksum(data.data(), data.size());
}

/// The whole packet `FA FB COUNT DATA CHK_hi CHK_lo` for DATA (COUNT = DATA size + 2).
/// Throws std::invalid_argument when DATA is empty or longer than kMaxCount - 2 bytes.
std::vector<uint8_t> encodeArcosPacket(const std::vector<uint8_t>& data);
/// A command without argument (SYNC0..2, PULSE, OPEN, CLOSE, STOP, ESTOP).
std::vector<uint8_t> arcosCommand(uint8_t command);
/// A command with a signed integer argument, clamped to ±32767 (0x3B for ≥ 0, 0x1B with the absolute
/// value for < 0). E.g. ENABLE 1 = FA FB 06 04 3B 01 00 05 3B.
std::vector<uint8_t> arcosCommand(uint8_t command, int argument);

/// Splits a byte stream into ARCOS packets. Only packets whose checksum matches are returned: a corrupted
/// packet is counted and dropped, and scanning restarts at the byte after its first header byte, so one
/// bad byte never swallows the packets after it (unlike p2os, whose check `(chk == (hi<<8)) | lo` accepts
/// nearly anything). Not thread-safe.
class ArcosPacketParser
{
public:
  /// Appends bytes; returns the DATA of each complete, verified packet in arrival order.
  std::vector<std::vector<uint8_t>> feed(const uint8_t* bytes, size_t size);
  std::vector<std::vector<uint8_t>> feed(const std::vector<uint8_t>& bytes) { return feed(bytes.data(), bytes.size()); }
  /// Packets dropped for a wrong checksum or an impossible count since construction.
  unsigned long rejected() const { return rejected_; }
  /// Bytes skipped while looking for a header.
  unsigned long skippedBytes() const { return skipped_; }
  void clear() { buffer_.clear(); }

private:
  std::vector<uint8_t> buffer_;
  unsigned long rejected_ = 0;
  unsigned long skipped_ = 0;
};

/// Little-endian signed 16-bit at data[offset]; throws std::out_of_range past the end.
int16_t readInt16(const std::vector<uint8_t>& data, size_t offset);
uint16_t readUint16(const std::vector<uint8_t>& data, size_t offset);

/// The NUL-terminated strings of a SYNC2 reply (robot name, class, subclass), after its command byte.
std::vector<std::string> syncReplyStrings(const std::vector<uint8_t>& data);
}  // namespace pioneer_driver
