#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace phantomx_driver
{
/// Dynamixel protocol 1.0 instructions (emanual.robotis.com, protocol1; DynamixelSDK protocol1_packet_handler).
enum DynamixelInstruction : uint8_t
{
  kPing = 1,
  kRead = 2,
  kWrite = 3,
  kRegWrite = 4,
  kAction = 5,
  kReset = 6,
  kSyncWrite = 0x83,
};

/// Status error bits.
enum DynamixelError : uint8_t
{
  kErrorVoltage = 1,
  kErrorAngleLimit = 2,
  kErrorOverheat = 4,
  kErrorRange = 8,
  kErrorChecksum = 16,
  kErrorOverload = 32,
  kErrorInstruction = 64,
};

/// AX-12(A) control table addresses.
enum Ax12Address : uint8_t
{
  kAddrId = 3,
  kAddrTorqueEnable = 24,
  kAddrGoalPosition = 30,        ///< 2 bytes, 0–1023 over 300°
  kAddrMovingSpeed = 32,         ///< 2 bytes, 0.111 rpm units, 0 = maximum
  kAddrPresentPosition = 36,     ///< 2 bytes
  kAddrPresentSpeed = 38,        ///< 2 bytes, bit 10 = direction
  kAddrPresentLoad = 40,         ///< 2 bytes, bit 10 = direction
  kAddrPresentVoltage = 42,      ///< 0.1 V
  kAddrPresentTemperature = 43,  ///< °C
};

constexpr uint8_t kBroadcastId = 0xFE;

/// Checksum of a protocol 1.0 packet: ~(ID + LEN + INST/ERR + Σ params) & 0xFF, header excluded.
uint8_t dynamixelChecksum(uint8_t id, uint8_t length, uint8_t instruction, const std::vector<uint8_t>& params);

/// `FF FF ID LEN INST P.. CHK` with LEN = params + 2. Goal 512 to ID 1 = FF FF 01 05 03 1E 00 02 D6.
/// Throws std::invalid_argument when the packet would exceed 255 bytes of LEN.
std::vector<uint8_t> encodeDynamixelPacket(uint8_t id, uint8_t instruction, const std::vector<uint8_t>& params);
std::vector<uint8_t> pingPacket(uint8_t id);
std::vector<uint8_t> readPacket(uint8_t id, uint8_t address, uint8_t length);
std::vector<uint8_t> writePacket(uint8_t id, uint8_t address, const std::vector<uint8_t>& data);
/// SYNC_WRITE to the broadcast ID: params `address, L, {id, L bytes}×n` (LEN = (L+1)·n + 4). Throws
/// std::invalid_argument when the entries' data lengths differ or are empty.
std::vector<uint8_t> syncWritePacket(uint8_t address,
                                     const std::vector<std::pair<uint8_t, std::vector<uint8_t>>>& entries);

/// A decoded packet: for status packets `code` is the error byte, for instructions the instruction.
struct DynamixelPacket
{
  uint8_t id = 0;
  uint8_t code = 0;
  std::vector<uint8_t> params;
};

/// Splits a byte stream into protocol 1.0 packets, returning only those whose checksum matches; the rest
/// are counted and skipped from the byte after their header. Not thread-safe.
class DynamixelPacketParser
{
public:
  std::vector<DynamixelPacket> feed(const std::vector<uint8_t>& bytes);
  unsigned long rejected() const { return rejected_; }
  void clear() { buffer_.clear(); }

private:
  std::vector<uint8_t> buffer_;
  unsigned long rejected_ = 0;
};

/// Little-endian 16-bit helpers.
inline std::vector<uint8_t> le16(int v)
{
  return {static_cast<uint8_t>(v & 0xFF), static_cast<uint8_t>((v >> 8) & 0xFF)};
}
inline int fromLe16(const std::vector<uint8_t>& d, size_t i)
{
  return d.at(i) | (d.at(i + 1) << 8);
}
}  // namespace phantomx_driver
