#include "phantomx_driver/dynamixel_packet.hpp"

#include <stdexcept>
#include <string>

namespace phantomx_driver
{
uint8_t dynamixelChecksum(uint8_t id, uint8_t length, uint8_t instruction, const std::vector<uint8_t>& params)
{
  unsigned sum = id + length + instruction;
  for (uint8_t p : params)
    sum += p;
  return static_cast<uint8_t>(~sum & 0xFF);
}

std::vector<uint8_t> encodeDynamixelPacket(uint8_t id, uint8_t instruction, const std::vector<uint8_t>& params)
{
  if (params.size() + 2 > 250)
    throw std::invalid_argument("encodeDynamixelPacket: " + std::to_string(params.size()) + " parameters, at most 248");
  const uint8_t length = static_cast<uint8_t>(params.size() + 2);
  // Reserved, then appended: GCC 12 warns (-Warray-bounds, a false positive) on insert after a braced list.
  std::vector<uint8_t> p;
  p.reserve(params.size() + 6);
  for (uint8_t b : {uint8_t{0xFF}, uint8_t{0xFF}, id, length, instruction})
    p.push_back(b);
  p.insert(p.end(), params.begin(), params.end());
  p.push_back(dynamixelChecksum(id, length, instruction, params));
  return p;
}

std::vector<uint8_t> pingPacket(uint8_t id)
{
  return encodeDynamixelPacket(id, kPing, {});
}

std::vector<uint8_t> readPacket(uint8_t id, uint8_t address, uint8_t length)
{
  return encodeDynamixelPacket(id, kRead, {address, length});
}

std::vector<uint8_t> writePacket(uint8_t id, uint8_t address, const std::vector<uint8_t>& data)
{
  std::vector<uint8_t> params;
  params.reserve(data.size() + 1);
  params.push_back(address);
  params.insert(params.end(), data.begin(), data.end());
  return encodeDynamixelPacket(id, kWrite, params);
}

std::vector<uint8_t> syncWritePacket(uint8_t address,
                                     const std::vector<std::pair<uint8_t, std::vector<uint8_t>>>& entries)
{
  if (entries.empty() || entries.front().second.empty())
    throw std::invalid_argument("syncWritePacket: no entries or empty data");
  const size_t l = entries.front().second.size();
  std::vector<uint8_t> params{address, static_cast<uint8_t>(l)};
  for (const auto& [id, data] : entries)
  {
    if (data.size() != l)
      throw std::invalid_argument("syncWritePacket: entries of different lengths");
    params.push_back(id);
    params.insert(params.end(), data.begin(), data.end());
  }
  return encodeDynamixelPacket(kBroadcastId, kSyncWrite, params);
}

std::vector<DynamixelPacket> DynamixelPacketParser::feed(const std::vector<uint8_t>& bytes)
{
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
  std::vector<DynamixelPacket> out;
  size_t pos = 0;
  while (true)
  {
    while (pos + 1 < buffer_.size() && !(buffer_[pos] == 0xFF && buffer_[pos + 1] == 0xFF))
      ++pos;
    if (pos + 4 > buffer_.size())
      break;
    // FF FF FF ... : the id cannot be 0xFF, so step on to the last of a run of 0xFF.
    if (buffer_[pos + 2] == 0xFF)
    {
      ++pos;
      continue;
    }
    const uint8_t id = buffer_[pos + 2];
    const uint8_t length = buffer_[pos + 3];
    if (length < 2)
    {
      ++rejected_;
      ++pos;
      continue;
    }
    if (pos + 4 + length > buffer_.size())
      break;
    const uint8_t code = buffer_[pos + 4];
    std::vector<uint8_t> params(buffer_.begin() + static_cast<std::ptrdiff_t>(pos + 5),
                                buffer_.begin() + static_cast<std::ptrdiff_t>(pos + 3 + length));
    const uint8_t chk = buffer_[pos + 3 + length];
    if (chk != dynamixelChecksum(id, length, code, params))
    {
      ++rejected_;
      ++pos;
      continue;
    }
    out.push_back({id, code, std::move(params)});
    pos += 4 + length;
  }
  buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(std::min(pos, buffer_.size())));
  return out;
}
}  // namespace phantomx_driver
