#include "pioneer_driver/pioneer_connection.hpp"

#include <chrono>
#include <stdexcept>
#include <thread>

#include "biovision_common/steady_seconds.hpp"

namespace pioneer_driver
{
PioneerConnection::PioneerConnection(const PioneerParameters& parameters) : p_(parameters)
{
  p_.validate();
}

PioneerConnection::~PioneerConnection()
{
  if (status_.connected)
  {
    try
    {
      port_.write(arcosCommand(kVel, 0));
      port_.write(arcosCommand(kRvel, 0));
      port_.write(arcosCommand(kClose));
    }
    catch (const std::exception&)
    {
    }
  }
}

void PioneerConnection::setMotionLimits(const PioneerParameters& parameters)
{
  PioneerParameters next = p_;
  next.max_linear_speed = parameters.max_linear_speed;
  next.max_angular_speed = parameters.max_angular_speed;
  next.cmd_vel_timeout = parameters.cmd_vel_timeout;
  next.validate();
  p_ = next;
}

void PioneerConnection::setCommand(double linear_m_s, double angular_rad_s, double now)
{
  command_v_ = linear_m_s;
  command_w_ = angular_rad_s;
  command_time_ = now;
}

std::vector<uint8_t> PioneerConnection::awaitPacket(double timeout)
{
  const double end = biovision_common::steadySeconds() + timeout;
  while (true)
  {
    const double left = end - biovision_common::steadySeconds();
    if (left <= 0.0)
      return {};
    const auto bytes = port_.read(256, left);
    auto packets = parser_.feed(bytes);
    if (!packets.empty())
      return packets.front();  // the handshake is strictly request/answer
  }
}

void PioneerConnection::connect(double now)
{
  const double started =
      biovision_common::steadySeconds();  // the handshake can take seconds: `now` is advanced by its length below
  port_.open(p_.port, p_.baud);
  parser_ = ArcosPacketParser();
  bool synced = false;
  for (int attempt = 0; attempt < 3 && !synced; ++attempt)
  {
    port_.write(arcosCommand(kSync0));
    const auto reply = awaitPacket(p_.sync_timeout);
    if (!reply.empty() && reply.size() == 1 && reply[0] == kSync0)
      synced = true;
    else if (!reply.empty())
    {
      // A session is still open (SIPs or other traffic): close it and start over.
      port_.write(arcosCommand(kClose));
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      port_.flushInput();
      parser_ = ArcosPacketParser();
    }
  }
  if (!synced)
    throw std::runtime_error("no SYNC0 echo from " + p_.port + " at " + std::to_string(p_.baud) +
                             " bit/s (robot off, wrong port or baud?)");
  port_.write(arcosCommand(kSync1));
  auto reply = awaitPacket(p_.sync_timeout);
  if (reply.empty() || reply[0] != kSync1)
    throw std::runtime_error("no SYNC1 echo from " + p_.port);
  port_.write(arcosCommand(kSync2));
  reply = awaitPacket(p_.sync_timeout);
  if (reply.empty() || reply[0] != kSync2)
    throw std::runtime_error("no SYNC2 reply from " + p_.port);
  const auto names = syncReplyStrings(reply);
  // A real controller answers with its name, class and subclass; a port that echoes what it is sent (a
  // loopback plug, a terminal) returns the bare SYNC2 and passed the two echo steps above.
  if (names.size() < 3 || names[0].empty())
    throw std::runtime_error("the SYNC2 reply from " + p_.port +
                             " carries no robot name, class and subclass (a port echoing the driver, not a robot?)");
  status_.robot_name = names.size() > 0 ? names[0] : "";
  status_.robot_class = names.size() > 1 ? names[1] : "";
  status_.robot_subclass = names.size() > 2 ? names[2] : "";
  port_.write(arcosCommand(kOpen));
  port_.write(arcosCommand(kPulse));
  if (p_.enable_motors)
    port_.write(arcosCommand(kEnable, 1));
  port_.write(arcosCommand(kVel, 0));
  port_.write(arcosCommand(kRvel, 0));
  status_.commanded = ArcosVelocity{};
  status_.connected = true;
  status_.connects++;
  rejected_base_ = parser_.rejected();
  // Grace until the first SIP from the end of the handshake, not its start: a handshake answered on the
  // third SYNC0 took 1.5 s of the 1 s sip_timeout, and the new session was dropped 20 ms after OPEN.
  now += biovision_common::steadySeconds() - started;
  last_sip_ = now;
  last_tx_ = now;
}

void PioneerConnection::send(const std::vector<uint8_t>& packet, double now)
{
  port_.write(packet);
  last_tx_ = now;
}

void PioneerConnection::lose(const std::string& why, double now)
{
  if (status_.connected)
    status_.losses++;
  status_.connected = false;
  status_.last_error = why;
  status_.commanded = ArcosVelocity{};
  port_.close();
  next_attempt_ = now + p_.reconnect_period;
}

void PioneerConnection::disconnect(const std::string& why, double now)
{
  if (status_.connected)
  {
    try
    {
      port_.write(arcosCommand(kVel, 0));
      port_.write(arcosCommand(kRvel, 0));
      port_.write(arcosCommand(kClose));
    }
    catch (const std::exception&)
    {
    }
  }
  lose(why, now);
}

std::vector<StandardSip> PioneerConnection::spinOnce(double now, double read_timeout)
{
  std::vector<StandardSip> sips;
  if (!status_.connected)
  {
    if (now < next_attempt_)
    {
      std::this_thread::sleep_for(std::chrono::duration<double>(read_timeout));
      return sips;
    }
    try
    {
      connect(now);
    }
    catch (const std::exception& e)
    {
      lose(std::string("connect: ") + e.what(), now);
      return sips;
    }
  }
  try
  {
    const auto bytes = port_.read(512, read_timeout);
    for (const auto& data : parser_.feed(bytes))
    {
      if (!isStandardSip(data))
        continue;  // configuration, encoder or other SIPs: not used
      try
      {
        sips.push_back(parseStandardSip(data));
        status_.sips++;
        last_sip_ = now;
      }
      catch (const std::invalid_argument&)
      {
        status_.rejected_packets++;
      }
    }
    status_.rejected_packets += parser_.rejected() - rejected_base_;
    rejected_base_ = parser_.rejected();

    const bool fresh = now - command_time_ <= p_.cmd_vel_timeout;
    status_.watchdog_stopped = !fresh;
    const ArcosVelocity target = fresh ? toArcosVelocity(command_v_, command_w_, p_) : ArcosVelocity{};
    // The setpoint goes out when it changes and again after every pulse_period without one (instead of a
    // bare PULSE): a lost packet, a stop above all, is repeated, and any command keeps ARCOS's watchdog fed.
    if (target != status_.commanded || now - last_tx_ >= p_.pulse_period)
    {
      send(arcosCommand(kVel, target.vel_mm_s), now);
      send(arcosCommand(kRvel, target.rvel_deg_s), now);
      status_.commanded = target;
    }
    if (now - last_sip_ > p_.sip_timeout)
      throw std::runtime_error("no valid SIP for " + std::to_string(now - last_sip_) + " s");
  }
  catch (const std::exception& e)
  {
    // Stop and CLOSE before the port goes: when only the robot-to-PC direction died, the base would
    // otherwise keep its last setpoint, fed by the reconnection's SYNC0s (a PULSE to an open session).
    disconnect(e.what(), now);
  }
  return sips;
}
}  // namespace pioneer_driver
