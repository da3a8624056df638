#pragma once

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "biovision_common/serial_port.hpp"
#include "pioneer_driver/arcos_packet.hpp"
#include "pioneer_driver/pioneer_odometry.hpp"

namespace pioneer_driver
{
/// A Pioneer 3DX controller speaking ARCOS on the master side of a pseudo-terminal, for tests and for
/// running the stack without the robot (tool `pioneer_emulator`). SYNC0/1/2 handshake (name
/// "BioVisionEmulator", class "Pioneer", subclass "p3dx-sh"), OPEN/CLOSE/PULSE, ENABLE, VEL/RVEL (applied
/// at once, capped to the P3DX 2200 mm/s, 500°/s); the pose is integrated exactly on arcs; a standard SIP
/// every `sip_period`; its own watchdog zeroes the setpoints after 2 s without a command, as ARCOS does.
/// Packets with a wrong checksum are counted and ignored. Runs its own thread; the accessors are
/// thread-safe.
class ArcosEmulator
{
public:
  /// Opens the pty (and `link_path` → its slave when given) and starts the thread. Throws
  /// biovision_common::SerialError when no pty can be made.
  explicit ArcosEmulator(const std::string& link_path = "", double sip_period = 0.1);
  ~ArcosEmulator();
  ArcosEmulator(const ArcosEmulator&) = delete;
  ArcosEmulator& operator=(const ArcosEmulator&) = delete;

  /// The device a driver opens: the link when given, else the pty slave.
  std::string port() const;
  bool sessionOpen() const;
  bool motorsEnabled() const;
  ArcosVelocity setpoint() const;  ///< the VEL [mm/s] and RVEL [deg/s] in force
  /// How many packets of command `command` arrived with a valid checksum.
  unsigned long commandCount(uint8_t command) const;
  unsigned long badChecksums() const;  ///< packets from the driver rejected
  unsigned long sipsSent() const;
  double x() const;    ///< [m] true pose in the controller's frame
  double y() const;    ///< [m]
  double yaw() const;  ///< [rad]
  /// Largest |VEL| [mm/s] and |RVEL| [deg/s] ever commanded (the caps a driver must respect).
  int maxAbsVel() const;
  int maxAbsRvel() const;

  /// Corrupts one byte of each of the next `n` SIPs (a noisy cable).
  void corruptNextSips(int n);
  /// Loses the next `n` packets of command `command` from the driver (a lost packet on the line): they are
  /// neither counted nor applied.
  void dropNext(uint8_t command, int n);
  /// Sends `bytes` raw, as line noise.
  void injectBytes(const std::vector<uint8_t>& bytes);
  void setStallBumpers(uint16_t bits);
  void setBattery(double volts);
  /// Closes the pty: the driver's port hangs up, as if the cable were pulled. The session state is kept
  /// (a real controller keeps running), the watchdog will stop the motors.
  void pullCable();
  /// A new pty behind the same link, as if the cable were plugged back in.
  void plugIn();

private:
  void run();
  void handle(const std::vector<uint8_t>& data, double now);
  void sendSip();
  void reply(const std::vector<uint8_t>& data);

  std::string link_path_;
  double sip_period_;
  mutable std::mutex mutex_;
  std::unique_ptr<biovision_common::PseudoTerminal> pty_;
  ArcosPacketParser parser_;
  int sync_state_ = 0;  // 0 wait SYNC0, 1 wait SYNC1, 2 wait SYNC2, 3 wait OPEN, 4 open
  bool motors_ = false;
  ArcosVelocity setpoint_;
  std::map<uint8_t, unsigned long> counts_;
  std::map<uint8_t, int> drop_;
  unsigned long sips_sent_ = 0;
  int corrupt_ = 0;
  uint16_t stall_bumpers_ = 0;
  uint8_t battery_ = 125;
  int max_vel_ = 0, max_rvel_ = 0;
  double x_mm_ = 0.0, y_mm_ = 0.0, th_ = 0.0;
  double last_command_ = 0.0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};
}  // namespace pioneer_driver
