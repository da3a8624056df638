#include "pioneer_driver/standard_sip.hpp"

#include <stdexcept>
#include <string>

#include "pioneer_driver/arcos_packet.hpp"

namespace pioneer_driver
{
namespace
{
constexpr size_t kFixedSize = 20;  // type, 5 ints, battery, 3 uints/ints, compass, sonar count

void put16(std::vector<uint8_t>& d, int v)
{
  d.push_back(static_cast<uint8_t>(v & 0xFF));
  d.push_back(static_cast<uint8_t>((v >> 8) & 0xFF));
}
}  // namespace

StandardSip parseStandardSip(const std::vector<uint8_t>& data)
{
  if (!isStandardSip(data))
    throw std::invalid_argument("parseStandardSip: not a standard SIP (type byte 0x32/0x33)");
  if (data.size() < kFixedSize)
    throw std::invalid_argument("parseStandardSip: " + std::to_string(data.size()) + " bytes, fewer than the " +
                                std::to_string(kFixedSize) + " of the fixed part");
  StandardSip s;
  s.moving = data[0] == 0x33;
  s.xpos = readUint16(data, 1) & 0x7FFF;
  s.ypos = readUint16(data, 3) & 0x7FFF;
  s.thpos = readInt16(data, 5);
  s.left_velocity = readInt16(data, 7);
  s.right_velocity = readInt16(data, 9);
  s.battery = data[11];
  s.stall_bumpers = readUint16(data, 12);
  s.control = readInt16(data, 14);
  s.flags = readUint16(data, 16);
  s.compass = data[18];
  const size_t n = data[19];
  if (data.size() < kFixedSize + 3 * n)
    throw std::invalid_argument("parseStandardSip: " + std::to_string(n) + " sonar readings announced, " +
                                std::to_string(data.size() - kFixedSize) + " bytes left");
  for (size_t i = 0; i < n; ++i)
    s.sonars.emplace_back(data[kFixedSize + 3 * i], readUint16(data, kFixedSize + 3 * i + 1));
  return s;
}

std::vector<uint8_t> encodeStandardSip(const StandardSip& s)
{
  std::vector<uint8_t> d{static_cast<uint8_t>(s.moving ? 0x33 : 0x32)};
  put16(d, s.xpos & 0x7FFF);
  put16(d, s.ypos & 0x7FFF);
  put16(d, s.thpos);
  put16(d, s.left_velocity);
  put16(d, s.right_velocity);
  d.push_back(s.battery);
  put16(d, s.stall_bumpers);
  put16(d, s.control);
  put16(d, s.flags);
  d.push_back(s.compass);
  d.push_back(static_cast<uint8_t>(s.sonars.size()));
  for (const auto& [number, range] : s.sonars)
  {
    d.push_back(number);
    put16(d, range);
  }
  for (int i = 0; i < 8; ++i)  // TIMER (2), ANALOG, DIGIN, DIGOUT, and padding
    d.push_back(0);
  return d;
}
}  // namespace pioneer_driver
