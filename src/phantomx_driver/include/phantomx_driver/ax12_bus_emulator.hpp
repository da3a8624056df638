#pragma once

#include <array>
#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "biovision_common/serial_port.hpp"
#include "phantomx_driver/dynamixel_packet.hpp"

namespace phantomx_driver
{
/// AX-12A servos on a Dynamixel 1.0 bus behind a pseudo-terminal, for tests and for running the stack
/// without the turret (tool `phantomx_emulator`). Each servo has a 50-byte control table with the factory
/// defaults, answers PING, READ and WRITE (status return level 2), takes SYNC_WRITE and broadcasts
/// silently, and moves towards its goal at its moving speed (0 = 59 rpm) while torque is on. A packet with
/// a bad checksum is counted and ignored (no reply). Errors can be injected and servos silenced. Runs its own
/// thread; the accessors are thread-safe.
class Ax12BusEmulator
{
public:
  /// Servos with the given IDs; `link_path` → the pty slave when given. Throws biovision_common::SerialError.
  explicit Ax12BusEmulator(const std::vector<uint8_t>& ids = {1, 2}, const std::string& link_path = "");
  ~Ax12BusEmulator();
  Ax12BusEmulator(const Ax12BusEmulator&) = delete;
  Ax12BusEmulator& operator=(const Ax12BusEmulator&) = delete;

  std::string port() const;
  /// Present position [ticks] (fractional while moving).
  double position(uint8_t id) const;
  int goal(uint8_t id) const;
  bool torqueOn(uint8_t id) const;
  int movingSpeed(uint8_t id) const;
  /// Every goal ever written to `id` stayed within [lo, hi] ticks?
  std::pair<int, int> goalRange(uint8_t id) const;
  unsigned long syncWrites() const;
  unsigned long badChecksums() const;
  /// Writes a 16-bit register directly (e.g. a stale goal left from an earlier session).
  void setRegister16(uint8_t id, uint8_t address, int value);
  /// Sets error bits reported in every status of `id` (e.g. kErrorOverload); 0 clears them. An overload
  /// also switches the torque off, as the AX-12's alarm shutdown does.
  void injectError(uint8_t id, uint8_t bits);
  /// A silent servo ignores everything (a cut cable to one servo).
  void setSilent(uint8_t id, bool silent);
  /// Corrupts the checksum of the next `n` status packets.
  void corruptNextReplies(int n);
  /// Loses the next `n` SYNC_WRITE broadcasts (a lost packet: no servo answers a broadcast).
  void dropNextSyncWrites(int n);
  /// The next `n` READs of `id` report `ticks` as the present position, checksum intact (a servo or line
  /// fault the checksum does not catch; 0-1023 is the AX-12's range).
  void misreportPosition(uint8_t id, int ticks, int n);
  void pullCable();
  void plugIn();

private:
  struct Servo
  {
    std::array<uint8_t, 50> table{};
    double position = 512.0;
    uint8_t error = 0;
    bool silent = false;
    int misreport_ticks = 0, misreports = 0;
    int goal_min = 1023, goal_max = 0;
  };
  void run();
  void handle(const DynamixelPacket& p);
  void reply(Servo& s, uint8_t id, const std::vector<uint8_t>& params);
  void write(Servo& s, uint8_t address, const std::vector<uint8_t>& data, size_t from);

  std::string link_path_;
  mutable std::mutex mutex_;
  std::unique_ptr<biovision_common::PseudoTerminal> pty_;
  DynamixelPacketParser parser_;
  std::map<uint8_t, Servo> servos_;
  unsigned long sync_writes_ = 0;
  int corrupt_ = 0;
  int drop_sync_writes_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};
}  // namespace phantomx_driver
