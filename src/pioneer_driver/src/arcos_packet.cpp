#include "pioneer_driver/arcos_packet.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace pioneer_driver
{
uint16_t arcosChecksum(const uint8_t* data, size_t size)
{
  uint32_t c = 0;
  size_t i = 0;
  for (; i + 1 < size; i += 2)
  {
    c += (static_cast<uint32_t>(data[i]) << 8) | data[i + 1];
    c &= 0xFFFF;
  }
  if (i < size)
    c ^= data[i];
  return static_cast<uint16_t>(c);
}

std::vector<uint8_t> encodeArcosPacket(const std::vector<uint8_t>& data)
{
  if (data.empty() || data.size() + 2 > kMaxCount)
    throw std::invalid_argument("encodeArcosPacket: " + std::to_string(data.size()) + " data bytes outside [1, " +
                                std::to_string(kMaxCount - 2) + "]");
  // Reserved, then appended: GCC 12 warns (-Warray-bounds, a false positive) on insert after a braced list.
  std::vector<uint8_t> p;
  p.reserve(data.size() + 5);
  p.push_back(kHeader0);
  p.push_back(kHeader1);
  p.push_back(static_cast<uint8_t>(data.size() + 2));
  p.insert(p.end(), data.begin(), data.end());
  const uint16_t c = arcosChecksum(data);
  p.push_back(static_cast<uint8_t>(c >> 8));
  p.push_back(static_cast<uint8_t>(c & 0xFF));
  return p;
}

std::vector<uint8_t> arcosCommand(uint8_t command)
{
  return encodeArcosPacket({command});
}

std::vector<uint8_t> arcosCommand(uint8_t command, int argument)
{
  const int a = std::clamp(argument, -32767, 32767);
  const int m = std::abs(a);
  return encodeArcosPacket({command, a >= 0 ? kArgPositive : kArgNegative, static_cast<uint8_t>(m & 0xFF),
                            static_cast<uint8_t>((m >> 8) & 0xFF)});
}

std::vector<std::vector<uint8_t>> ArcosPacketParser::feed(const uint8_t* bytes, size_t size)
{
  buffer_.insert(buffer_.end(), bytes, bytes + size);
  std::vector<std::vector<uint8_t>> packets;
  size_t pos = 0;
  while (true)
  {
    // Find a header.
    size_t start = pos;
    while (start + 1 < buffer_.size() && !(buffer_[start] == kHeader0 && buffer_[start + 1] == kHeader1))
      ++start;
    skipped_ += start - pos;
    pos = start;
    if (pos + 3 > buffer_.size())
      break;
    const size_t count = buffer_[pos + 2];
    if (count < 3 || count > kMaxCount)
    {
      ++rejected_;
      pos += 1;
      continue;
    }
    if (pos + 3 + count > buffer_.size())
      break;  // wait for the rest
    const uint8_t* data = buffer_.data() + pos + 3;
    const size_t n = count - 2;
    const uint16_t got = static_cast<uint16_t>((buffer_[pos + 3 + n] << 8) | buffer_[pos + 3 + n + 1]);
    if (got != arcosChecksum(data, n))
    {
      ++rejected_;
      pos += 1;  // rescan from the next byte: a good packet may start inside this one
      continue;
    }
    packets.emplace_back(data, data + n);
    pos += 3 + count;
  }
  // Keep an unfinished tail (a lone 0xFA may be the start of the next header).
  if (pos >= buffer_.size())
    buffer_.clear();
  else
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(pos));
  return packets;
}

int16_t readInt16(const std::vector<uint8_t>& data, size_t offset)
{
  return static_cast<int16_t>(readUint16(data, offset));
}

uint16_t readUint16(const std::vector<uint8_t>& data, size_t offset)
{
  if (offset + 2 > data.size())
    throw std::out_of_range("ARCOS packet: 2 bytes at " + std::to_string(offset) + " past its end (" +
                            std::to_string(data.size()) + " bytes)");
  return static_cast<uint16_t>(data[offset] | (data[offset + 1] << 8));
}

std::vector<std::string> syncReplyStrings(const std::vector<uint8_t>& data)
{
  std::vector<std::string> out;
  std::string s;
  for (size_t i = 1; i < data.size(); ++i)
  {
    if (data[i] == 0)
    {
      out.push_back(s);
      s.clear();
    }
    else
      s.push_back(static_cast<char>(data[i]));
  }
  if (!s.empty())
    out.push_back(s);
  return out;
}
}  // namespace pioneer_driver
