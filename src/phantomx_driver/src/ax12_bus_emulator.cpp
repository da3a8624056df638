#include "phantomx_driver/ax12_bus_emulator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "biovision_common/steady_seconds.hpp"

namespace phantomx_driver
{
namespace
{
constexpr double kTicksPerRpmSecond = 1023.0 / 300.0 * 360.0 / 60.0;  // ticks/s per rpm
}  // namespace

Ax12BusEmulator::Ax12BusEmulator(const std::vector<uint8_t>& ids, const std::string& link_path) : link_path_(link_path)
{
  for (uint8_t id : ids)
  {
    Servo s;
    s.table[0] = 12;  // model number AX-12 (low byte)
    s.table[kAddrId] = id;
    s.table[4] = 1;    // 1 Mbps
    s.table[5] = 250;  // return delay
    s.table[8] = 0xFF;
    s.table[9] = 0x03;  // CCW angle limit 1023
    s.table[16] = 2;    // status return level
    s.table[kAddrGoalPosition] = 0x00;
    s.table[kAddrGoalPosition + 1] = 0x02;  // goal 512
    s.table[34] = 0xFF;
    s.table[35] = 0x03;  // torque limit
    s.table[kAddrPresentVoltage] = 120;
    s.table[kAddrPresentTemperature] = 35;
    servos_[id] = s;
  }
  pty_ = std::make_unique<biovision_common::PseudoTerminal>(link_path_);
  thread_ = std::thread([this] { run(); });
}

Ax12BusEmulator::~Ax12BusEmulator()
{
  stop_ = true;
  if (thread_.joinable())
    thread_.join();
}

std::string Ax12BusEmulator::port() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return link_path_.empty() && pty_ ? pty_->slavePath() : link_path_;
}

double Ax12BusEmulator::position(uint8_t id) const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return servos_.at(id).position;
}

int Ax12BusEmulator::goal(uint8_t id) const
{
  std::lock_guard<std::mutex> lock(mutex_);
  const auto& t = servos_.at(id).table;
  return t[kAddrGoalPosition] | (t[kAddrGoalPosition + 1] << 8);
}

bool Ax12BusEmulator::torqueOn(uint8_t id) const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return servos_.at(id).table[kAddrTorqueEnable] != 0;
}

int Ax12BusEmulator::movingSpeed(uint8_t id) const
{
  std::lock_guard<std::mutex> lock(mutex_);
  const auto& t = servos_.at(id).table;
  return t[kAddrMovingSpeed] | (t[kAddrMovingSpeed + 1] << 8);
}

std::pair<int, int> Ax12BusEmulator::goalRange(uint8_t id) const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return {servos_.at(id).goal_min, servos_.at(id).goal_max};
}

unsigned long Ax12BusEmulator::syncWrites() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return sync_writes_;
}

unsigned long Ax12BusEmulator::badChecksums() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return parser_.rejected();
}

void Ax12BusEmulator::setRegister16(uint8_t id, uint8_t address, int value)
{
  std::lock_guard<std::mutex> lock(mutex_);
  Servo& s = servos_.at(id);
  s.table.at(address) = static_cast<uint8_t>(value & 0xFF);
  s.table.at(address + 1) = static_cast<uint8_t>((value >> 8) & 0xFF);
}

void Ax12BusEmulator::dropNextSyncWrites(int n)
{
  std::lock_guard<std::mutex> lock(mutex_);
  drop_sync_writes_ = n;
}

void Ax12BusEmulator::misreportPosition(uint8_t id, int ticks, int n)
{
  std::lock_guard<std::mutex> lock(mutex_);
  Servo& s = servos_.at(id);
  s.misreport_ticks = ticks;
  s.misreports = n;
}

void Ax12BusEmulator::injectError(uint8_t id, uint8_t bits)
{
  std::lock_guard<std::mutex> lock(mutex_);
  Servo& s = servos_.at(id);
  s.error = bits;
  if ((bits & kErrorOverload) != 0)
    s.table[kAddrTorqueEnable] = 0;
}

void Ax12BusEmulator::setSilent(uint8_t id, bool silent)
{
  std::lock_guard<std::mutex> lock(mutex_);
  servos_.at(id).silent = silent;
}

void Ax12BusEmulator::corruptNextReplies(int n)
{
  std::lock_guard<std::mutex> lock(mutex_);
  corrupt_ = n;
}

void Ax12BusEmulator::pullCable()
{
  std::lock_guard<std::mutex> lock(mutex_);
  pty_.reset();
}

void Ax12BusEmulator::plugIn()
{
  std::lock_guard<std::mutex> lock(mutex_);
  pty_ = std::make_unique<biovision_common::PseudoTerminal>(link_path_);
  parser_.clear();
}

void Ax12BusEmulator::reply(Servo& s, uint8_t id, const std::vector<uint8_t>& params)
{
  auto packet = encodeDynamixelPacket(id, s.error, params);
  if (corrupt_ > 0)
  {
    packet.back() ^= 0x01;
    corrupt_--;
  }
  if (pty_)
    pty_->write(packet);
}

void Ax12BusEmulator::write(Servo& s, uint8_t address, const std::vector<uint8_t>& data, size_t from)
{
  for (size_t i = from; i < data.size(); ++i)
  {
    const size_t a = address + (i - from);
    if (a < 24 || a >= s.table.size() || (a >= 36 && a != 47))
      continue;  // EEPROM (IDs, limits) and read-only registers are not emulated as writable
    s.table[a] = data[i];
  }
  const int goal = s.table[kAddrGoalPosition] | (s.table[kAddrGoalPosition + 1] << 8);
  if (address <= kAddrGoalPosition + 1 && address + (data.size() - from) > kAddrGoalPosition)
  {
    s.goal_min = std::min(s.goal_min, goal);
    s.goal_max = std::max(s.goal_max, goal);
  }
}

void Ax12BusEmulator::handle(const DynamixelPacket& p)
{
  if (p.id == kBroadcastId)
  {
    if (p.code == kSyncWrite && p.params.size() >= 2 && drop_sync_writes_ > 0)
    {
      drop_sync_writes_--;
      return;
    }
    if (p.code == kSyncWrite && p.params.size() >= 2)
    {
      sync_writes_++;
      const uint8_t address = p.params[0], l = p.params[1];
      for (size_t i = 2; i + l < p.params.size() + 1; i += l + 1)
      {
        auto it = servos_.find(p.params[i]);
        if (it == servos_.end() || it->second.silent)
          continue;
        std::vector<uint8_t> data(p.params.begin() + static_cast<std::ptrdiff_t>(i + 1),
                                  p.params.begin() + static_cast<std::ptrdiff_t>(i + 1 + l));
        write(it->second, address, data, 0);
      }
    }
    return;
  }
  auto it = servos_.find(p.id);
  if (it == servos_.end() || it->second.silent)
    return;
  Servo& s = it->second;
  switch (p.code)
  {
    case kPing:
      reply(s, p.id, {});
      break;
    case kRead:
    {
      if (p.params.size() != 2)
        break;
      std::vector<uint8_t> out;
      int pos = static_cast<int>(std::lround(s.position));
      if (s.misreports > 0)
      {
        s.misreports--;
        pos = s.misreport_ticks;
      }
      s.table[kAddrPresentPosition] = static_cast<uint8_t>(pos & 0xFF);
      s.table[kAddrPresentPosition + 1] = static_cast<uint8_t>(pos >> 8);
      for (size_t a = p.params[0]; a < p.params[0] + p.params[1] && a < s.table.size(); ++a)
        out.push_back(s.table[a]);
      reply(s, p.id, out);
      break;
    }
    case kWrite:
      if (!p.params.empty())
        write(s, p.params[0], p.params, 1);
      reply(s, p.id, {});
      break;
    default:
      reply(s, p.id, {});
      break;
  }
}

void Ax12BusEmulator::run()
{
  double last = biovision_common::steadySeconds();
  while (!stop_)
  {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      std::vector<uint8_t> bytes;
      if (pty_)
        bytes = pty_->read(256, 0.0);
      for (const auto& p : parser_.feed(bytes))
        handle(p);
      const double now = biovision_common::steadySeconds(), dt = now - last;
      last = now;
      for (auto& [id, s] : servos_)
      {
        const int goal = s.table[kAddrGoalPosition] | (s.table[kAddrGoalPosition + 1] << 8);
        const int speed = s.table[kAddrMovingSpeed] | (s.table[kAddrMovingSpeed + 1] << 8);
        const double rpm = speed == 0 ? 59.0 : std::min(59.0, speed * 0.111);
        const double step = rpm * kTicksPerRpmSecond * dt;
        if (s.table[kAddrTorqueEnable] != 0)
          s.position += std::clamp(goal - s.position, -step, step);
        const double moving = s.table[kAddrTorqueEnable] != 0 && std::abs(goal - s.position) > 0.5 ? rpm : 0.0;
        const int v = static_cast<int>(std::lround(moving / 0.111)) | (goal < s.position ? 0x400 : 0);
        s.table[kAddrPresentSpeed] = static_cast<uint8_t>(v & 0xFF);
        s.table[kAddrPresentSpeed + 1] = static_cast<uint8_t>(v >> 8);
        s.table[46] = moving > 0.0 ? 1 : 0;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}
}  // namespace phantomx_driver
