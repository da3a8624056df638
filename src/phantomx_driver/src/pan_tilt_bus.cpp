#include "phantomx_driver/pan_tilt_bus.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "biovision_common/steady_seconds.hpp"

namespace phantomx_driver
{
std::string describeErrorBits(uint8_t error)
{
  static const std::pair<uint8_t, const char*> kNames[] = {
      {kErrorVoltage, "input voltage"},  {kErrorAngleLimit, "angle limit"},
      {kErrorOverheat, "overheat"},      {kErrorRange, "range"},
      {kErrorChecksum, "checksum"},      {kErrorOverload, "overload"},
      {kErrorInstruction, "instruction"}};
  std::string s;
  for (const auto& [bit, name] : kNames)
    if ((error & bit) != 0)
      s += (s.empty() ? "" : ", ") + std::string(name);
  return s;
}

PanTiltBus::PanTiltBus(const PhantomXParameters& parameters) : p_(parameters)
{
  p_.validate();
  joints_[kPan] = Ax12Joint{
      p_.pan_joint, static_cast<uint8_t>(p_.pan_id), p_.pan_offset, p_.pan_direction, p_.pan_lower, p_.pan_upper};
  joints_[kTilt] = Ax12Joint{
      p_.tilt_joint, static_cast<uint8_t>(p_.tilt_id), p_.tilt_offset, p_.tilt_direction, p_.tilt_lower, p_.tilt_upper};
  for (size_t i = 0; i < 2; ++i)
    setLimits(i, joints_[i].lower, joints_[i].upper);
  speed_ticks_ = movingSpeedTicks(p_.max_speed);
}

void PanTiltBus::setLimits(size_t index, double lower, double upper)
{
  if (!std::isfinite(lower) || !std::isfinite(upper) || lower > upper)
    throw std::invalid_argument("PanTiltBus: limits [" + std::to_string(lower) + ", " + std::to_string(upper) +
                                "] of " + joints_.at(index).name + " are not an interval");
  Ax12Joint& j = joints_.at(index);
  // What the servo can reach: ticks 0 and 1023 as joint angles.
  const double a = j.radians(0), b = j.radians(1023);
  j.lower = std::max(lower, std::min(a, b));
  j.upper = std::min(upper, std::max(a, b));
  if (j.lower > j.upper)
    throw std::invalid_argument("PanTiltBus: limits of " + j.name + " lie outside the servo's 300° range");
}

bool PanTiltBus::setGoal(size_t index, double rad)
{
  const int ticks = joints_.at(index).goalTicks(rad);
  if (ticks < 0)
    return false;
  goal_wanted_[index] = ticks;
  return joints_[index].withinLimits(rad);
}

std::optional<DynamixelPacket> PanTiltBus::transact(const std::vector<uint8_t>& packet, uint8_t id)
{
  port_.write(packet);
  const double end = biovision_common::steadySeconds() + p_.response_timeout;
  while (true)
  {
    const double left = end - biovision_common::steadySeconds();
    if (left <= 0.0)
      return std::nullopt;
    for (auto& reply : parser_.feed(port_.read(64, left)))
      if (reply.id == id)
        return reply;
  }
}

void PanTiltBus::fail(size_t index, const std::string& why, double now)
{
  ServoState& s = servos_[index];
  s.misses++;
  s.consecutive_misses++;
  if (s.alive && s.consecutive_misses >= p_.lost_after)
  {
    s.alive = false;
    last_error_ = why;
  }
  if (!s.alive)
    s.next_retry = now + p_.retry_period;
}

void PanTiltBus::poll(size_t index, double now)
{
  ServoState& s = servos_[index];
  const Ax12Joint& j = joints_[index];
  if (!s.alive && now < s.next_retry)
    return;
  // Goal, moving speed, torque limit, then present position .. temperature (30..43): the goal register is
  // read back, so a SYNC_WRITE lost on the line (broadcasts get no reply) is noticed and written again.
  constexpr int kFirst = kAddrGoalPosition, kCount = kAddrPresentTemperature + 1 - kFirst;
  const auto reply = transact(readPacket(j.id, kFirst, kCount), j.id);
  if (!reply || reply->params.size() != kCount)
  {
    fail(index, "servo " + std::to_string(j.id) + " (" + j.name + ") does not answer", now);
    return;
  }
  const auto& d = reply->params;
  const int goal_register = fromLe16(d, kAddrGoalPosition - kFirst);
  const int here = fromLe16(d, kAddrPresentPosition - kFirst);
  if (here > 1023 || goal_register > 1023)
  {
    // 10 bits on an AX-12: a wider value passed the checksum but is not a position.
    last_error_ = "servo " + std::to_string(j.id) + " (" + j.name + ") reported position " + std::to_string(here) +
                  ", goal " + std::to_string(goal_register) + ": outside 0-1023, reply ignored";
    fail(index, last_error_, now);
    return;
  }
  if (!s.alive)
  {
    // First contact or back after a loss: the goal register may hold anything from an earlier session, and
    // torque on drives the servo there at once. So: goal = where it is now (clamped into the limits), our
    // speed, then torque on (unless switched off for an overload); a wanted goal follows in the next step.
    const int hold = std::clamp(here, std::min(j.goalTicks(j.lower), j.goalTicks(j.upper)),
                                std::max(j.goalTicks(j.lower), j.goalTicks(j.upper)));
    transact(writePacket(j.id, kAddrGoalPosition, le16(hold)), j.id);
    transact(writePacket(j.id, kAddrMovingSpeed, le16(speed_ticks_)), j.id);
    if (!s.torque_off)
      transact(writePacket(j.id, kAddrTorqueEnable, {1}), j.id);
    s.goal_sent = hold;
    s.alive = true;
  }
  else if (!s.torque_off && s.goal_sent >= 0 && goal_register != s.goal_sent)
  {
    if (s.rewrites_in_a_row < kMaxGoalRewrites)
    {
      if (goal_wanted_[index] < 0)
        goal_wanted_[index] = s.goal_sent;  // the hold goal of the first contact: step() writes it again
      s.goal_sent = -1;
      s.goal_rewrites++;
      s.rewrites_in_a_row++;
    }
    else if (s.rewrites_in_a_row == kMaxGoalRewrites)
    {
      // Written and read back different kMaxGoalRewrites times: the servo does not keep it (its angle
      // limits in EEPROM?). Not written in a loop; a new goal tries again.
      s.rewrites_in_a_row++;
      last_error_ = "servo " + std::to_string(j.id) + " (" + j.name + ") does not keep goal " +
                    std::to_string(s.goal_sent) + " (reads back " + std::to_string(goal_register) +
                    "): its angle limits? not written again until the goal changes";
    }
  }
  else if (goal_register == s.goal_sent)
    s.rewrites_in_a_row = 0;
  s.consecutive_misses = 0;
  s.polls++;
  s.error = reply->code;
  s.position = j.radians(here);
  s.velocity = j.direction * presentSpeedRadPerS(fromLe16(d, kAddrPresentSpeed - kFirst));
  const int load = fromLe16(d, kAddrPresentLoad - kFirst);
  s.load = ((load & 0x400) != 0 ? -1.0 : 1.0) * (load & 0x3FF) / 1023.0;
  s.voltage = d[kAddrPresentVoltage - kFirst] * 0.1;
  s.temperature = d[kAddrPresentTemperature - kFirst];
  if ((s.error & kErrorOverload) != 0 && p_.torque_off_on_overload && !s.torque_off)
  {
    transact(writePacket(j.id, kAddrTorqueEnable, {0}), j.id);
    s.torque_off = true;
    last_error_ = "servo " + std::to_string(j.id) + " (" + j.name + ") overloaded: torque switched off";
  }
}

void PanTiltBus::step(double now)
{
  if (!port_.isOpen())
  {
    if (now < next_port_attempt_)
      return;
    try
    {
      port_.open(p_.port, p_.baud);
      parser_.clear();
    }
    catch (const std::exception& e)
    {
      last_error_ = e.what();
      next_port_attempt_ = now + p_.retry_period;
      return;
    }
  }
  try
  {
    std::vector<std::pair<uint8_t, std::vector<uint8_t>>> entries;
    for (size_t i = 0; i < 2; ++i)
    {
      ServoState& s = servos_[i];
      if (s.alive && !s.torque_off && goal_wanted_[i] >= 0 && goal_wanted_[i] != s.goal_sent)
      {
        if (s.goal_sent >= 0)
          s.rewrites_in_a_row = 0;  // a new goal, not a rewrite
        std::vector<uint8_t> data = le16(goal_wanted_[i]);
        const auto speed = le16(speed_ticks_);
        data.insert(data.end(), speed.begin(), speed.end());
        entries.emplace_back(joints_[i].id, data);
        s.goal_sent = goal_wanted_[i];
      }
    }
    if (!entries.empty())
      port_.write(syncWritePacket(kAddrGoalPosition, entries));  // broadcast: no reply
    for (size_t i = 0; i < 2; ++i)
      poll(i, now);
  }
  catch (const std::exception& e)
  {
    last_error_ = std::string("serial port lost: ") + e.what();
    port_.close();
    port_failures_++;
    for (auto& s : servos_)
    {
      s.alive = false;
      s.consecutive_misses = 0;
      s.next_retry = 0.0;
    }
    next_port_attempt_ = now + p_.retry_period;
  }
}
}  // namespace phantomx_driver
