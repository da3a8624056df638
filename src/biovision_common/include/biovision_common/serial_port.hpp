#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace biovision_common
{
/// Thrown when a serial port cannot be opened, configured, read or written; the message names the
/// device and the reason (errno text). A driver treats it as "cable pulled": close, report, reconnect.
struct SerialError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// A raw 8N1 serial port over POSIX termios (no flow control, no echo, no line discipline), for the
/// hardware drivers (ARCOS, Dynamixel). Also opens pseudo-terminals, which is how the tests and the
/// emulators stand in for the robot. Not thread-safe; one owner.
class SerialPort
{
public:
  SerialPort() = default;
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  /// Opens `device` at `baud` bits/s (one of 9600, 19200, 38400, 57600, 115200, 230400, 460800, 500000,
  /// 576000, 921600, 1000000). Throws SerialError naming the device, or std::invalid_argument for a baud
  /// rate termios does not have.
  void open(const std::string& device, int baud);
  void close();
  bool isOpen() const { return fd_ >= 0; }
  const std::string& device() const { return device_; }

  /// Writes all bytes (blocking). Throws SerialError when the port is gone.
  void write(const std::vector<uint8_t>& bytes);
  /// Reads what arrives within `timeout_s` seconds (up to `max_bytes`); empty on time-out. Throws
  /// SerialError when the other end vanished (EIO/hang-up), so a pulled cable is never a silent time-out.
  std::vector<uint8_t> read(size_t max_bytes, double timeout_s);
  /// Discards unread input.
  void flushInput();

  /// The termios speed constant for `baud`; throws std::invalid_argument when there is none.
  static unsigned int speedConstant(int baud);

private:
  int fd_ = -1;
  std::string device_;
};

/// A pseudo-terminal pair (openpty): the driver opens `slavePath()` like a serial device, an emulator
/// reads and writes the master side. Raw mode on both. Optionally a symlink to the slave at a fixed
/// path, so a launch file can name the port before the emulator exists.
class PseudoTerminal
{
public:
  /// Throws SerialError when no pty can be allocated or the link cannot be made.
  explicit PseudoTerminal(const std::string& link_path = "");
  ~PseudoTerminal();
  PseudoTerminal(const PseudoTerminal&) = delete;
  PseudoTerminal& operator=(const PseudoTerminal&) = delete;

  const std::string& slavePath() const { return slave_path_; }
  int masterFd() const { return master_; }
  /// Writes bytes to the master side (they arrive at the slave's reader). False when it is closed.
  bool write(const std::vector<uint8_t>& bytes);
  /// Reads from the master side within `timeout_s` (what the slave's owner wrote); empty on time-out.
  std::vector<uint8_t> read(size_t max_bytes, double timeout_s);
  /// Closes both sides (and removes the link): the slave's owner sees EIO/hang-up, like a pulled cable.
  void close();
  bool isOpen() const { return master_ >= 0; }

private:
  int master_ = -1;
  int slave_ = -1;
  std::string slave_path_;
  std::string link_path_;
};
}  // namespace biovision_common
