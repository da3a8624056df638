#include "pioneer_driver/arcos_emulator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "biovision_common/steady_seconds.hpp"
#include "pioneer_driver/standard_sip.hpp"

namespace pioneer_driver
{
namespace
{
constexpr double kDiffConv = 0.0056;     // P3DX DiffConvFactor
constexpr double kAngleConv = 0.001534;  // P3DX AngleConvFactor
constexpr double kWatchdog = 2.0;        // ARCOS default watchdog [s]
constexpr int kMaxVel = 2200, kMaxRvel = 500;
}  // namespace

ArcosEmulator::ArcosEmulator(const std::string& link_path, double sip_period)
  : link_path_(link_path), sip_period_(sip_period)
{
  pty_ = std::make_unique<biovision_common::PseudoTerminal>(link_path_);
  thread_ = std::thread([this] { run(); });
}

ArcosEmulator::~ArcosEmulator()
{
  stop_ = true;
  if (thread_.joinable())
    thread_.join();
}

std::string ArcosEmulator::port() const
{
  std::lock_guard<std::mutex> lock(mutex_);
  return link_path_.empty() && pty_ ? pty_->slavePath() : link_path_;
}

#define BIOVISION_LOCKED_GETTER(type, name, expr) \
  type ArcosEmulator::name() const                \
  {                                               \
    std::lock_guard<std::mutex> lock(mutex_);     \
    return expr;                                  \
  }
BIOVISION_LOCKED_GETTER(bool, sessionOpen, sync_state_ == 4)
BIOVISION_LOCKED_GETTER(bool, motorsEnabled, motors_)
BIOVISION_LOCKED_GETTER(ArcosVelocity, setpoint, setpoint_)
BIOVISION_LOCKED_GETTER(unsigned long, badChecksums, parser_.rejected())
BIOVISION_LOCKED_GETTER(unsigned long, sipsSent, sips_sent_)
BIOVISION_LOCKED_GETTER(double, x, x_mm_ * 1e-3)
BIOVISION_LOCKED_GETTER(double, y, y_mm_ * 1e-3)
BIOVISION_LOCKED_GETTER(double, yaw, normalizeAngle(th_))
BIOVISION_LOCKED_GETTER(int, maxAbsVel, max_vel_)
BIOVISION_LOCKED_GETTER(int, maxAbsRvel, max_rvel_)
#undef BIOVISION_LOCKED_GETTER

unsigned long ArcosEmulator::commandCount(uint8_t command) const
{
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = counts_.find(command);
  return it == counts_.end() ? 0 : it->second;
}

void ArcosEmulator::corruptNextSips(int n)
{
  std::lock_guard<std::mutex> lock(mutex_);
  corrupt_ = n;
}

void ArcosEmulator::injectBytes(const std::vector<uint8_t>& bytes)
{
  std::lock_guard<std::mutex> lock(mutex_);
  if (pty_)
    pty_->write(bytes);
}

void ArcosEmulator::setStallBumpers(uint16_t bits)
{
  std::lock_guard<std::mutex> lock(mutex_);
  stall_bumpers_ = bits;
}

void ArcosEmulator::setBattery(double volts)
{
  std::lock_guard<std::mutex> lock(mutex_);
  battery_ = static_cast<uint8_t>(std::clamp(std::lround(volts * 10.0), 0L, 255L));
}

void ArcosEmulator::pullCable()
{
  std::lock_guard<std::mutex> lock(mutex_);
  pty_.reset();
}

void ArcosEmulator::plugIn()
{
  std::lock_guard<std::mutex> lock(mutex_);
  pty_ = std::make_unique<biovision_common::PseudoTerminal>(link_path_);
  parser_.clear();
}

void ArcosEmulator::reply(const std::vector<uint8_t>& data)
{
  if (pty_)
    pty_->write(encodeArcosPacket(data));
}

void ArcosEmulator::dropNext(uint8_t command, int n)
{
  std::lock_guard<std::mutex> lock(mutex_);
  drop_[command] = n;
}

void ArcosEmulator::handle(const std::vector<uint8_t>& data, double now)
{
  const uint8_t cmd = data[0];
  if (drop_[cmd] > 0)
  {
    drop_[cmd]--;
    return;
  }
  counts_[cmd]++;
  auto intArg = [&]() -> int {
    if (data.size() < 4)
      return 0;
    const int m = data[2] | (data[3] << 8);
    return data[1] == kArgNegative ? -m : m;
  };
  if (sync_state_ < 3)
  {
    if (cmd == kSync0)
      sync_state_ = 0;  // a SYNC0 always restarts the handshake
    if (cmd == sync_state_)
    {
      if (cmd == kSync2)
      {
        std::vector<uint8_t> r{kSync2};
        for (const char* s : {"BioVisionEmulator", "Pioneer", "p3dx-sh"})
        {
          r.insert(r.end(), s, s + std::char_traits<char>::length(s));
          r.push_back(0);
        }
        reply(r);
      }
      else
        reply({cmd});
      sync_state_++;
    }
    else
      sync_state_ = 0;
    return;
  }
  if (sync_state_ == 3)
  {
    if (cmd == kOpen)
    {
      sync_state_ = 4;
      x_mm_ = y_mm_ = th_ = 0.0;
      last_command_ = now;
    }
    return;
  }
  // Open session.
  last_command_ = now;
  switch (cmd)
  {
    case kClose:
      sync_state_ = 0;
      motors_ = false;
      setpoint_ = {};
      break;
    case kEnable:
      motors_ = intArg() != 0;
      break;
    case kVel:
      setpoint_.vel_mm_s = std::clamp(intArg(), -kMaxVel, kMaxVel);
      max_vel_ = std::max(max_vel_, std::abs(intArg()));
      break;
    case kRvel:
      setpoint_.rvel_deg_s = std::clamp(intArg(), -kMaxRvel, kMaxRvel);
      max_rvel_ = std::max(max_rvel_, std::abs(intArg()));
      break;
    case kStop:
    case kEStop:
      setpoint_ = {};
      break;
    default:
      break;  // PULSE and the rest
  }
}

void ArcosEmulator::sendSip()
{
  const bool moving = motors_ && (setpoint_.vel_mm_s != 0 || setpoint_.rvel_deg_s != 0);
  StandardSip s;
  s.moving = moving;
  s.xpos = static_cast<uint16_t>(static_cast<long>(std::lround(x_mm_)) & 0x7FFF);
  s.ypos = static_cast<uint16_t>(static_cast<long>(std::lround(y_mm_)) & 0x7FFF);
  s.thpos = static_cast<int16_t>(std::lround(normalizeAngle(th_) / kAngleConv));
  const double v = moving ? setpoint_.vel_mm_s : 0.0;
  const double w = moving ? setpoint_.rvel_deg_s * M_PI / 180.0 : 0.0;
  s.left_velocity = static_cast<int16_t>(std::lround(v - w / kDiffConv));
  s.right_velocity = static_cast<int16_t>(std::lround(v + w / kDiffConv));
  s.battery = battery_;
  s.stall_bumpers = stall_bumpers_;
  s.flags = motors_ ? 1 : 0;
  auto packet = encodeArcosPacket(encodeStandardSip(s));
  if (corrupt_ > 0)
  {
    packet[5] ^= 0x5A;  // a payload byte: the checksum no longer matches
    corrupt_--;
  }
  if (pty_)
    pty_->write(packet);
  sips_sent_++;
}

void ArcosEmulator::run()
{
  double last = biovision_common::steadySeconds(), next_sip = last;
  while (!stop_)
  {
    std::vector<uint8_t> bytes;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (pty_)
        bytes = pty_->read(512, 0.0);
    }
    const double now = biovision_common::steadySeconds();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (const auto& p : parser_.feed(bytes))
        handle(p, now);
      if (sync_state_ == 4 && now - last_command_ > kWatchdog)
        setpoint_ = {};
      // Exact arc integration of the setpoint over dt.
      const double dt = now - last;
      if (sync_state_ == 4 && motors_)
      {
        const double v = setpoint_.vel_mm_s, w = setpoint_.rvel_deg_s * M_PI / 180.0;
        if (std::abs(w) < 1e-9)
        {
          x_mm_ += v * dt * std::cos(th_);
          y_mm_ += v * dt * std::sin(th_);
        }
        else
        {
          const double th1 = th_ + w * dt;
          x_mm_ += v / w * (std::sin(th1) - std::sin(th_));
          y_mm_ -= v / w * (std::cos(th1) - std::cos(th_));
          th_ = th1;
        }
      }
      if (sync_state_ == 4 && now >= next_sip)
      {
        sendSip();
        next_sip += sip_period_;
        if (next_sip < now)
          next_sip = now + sip_period_;
      }
    }
    last = now;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}
}  // namespace pioneer_driver
