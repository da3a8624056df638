#include "biovision_common/serial_port.hpp"

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace biovision_common
{
namespace
{
std::string errnoText()
{
  return std::strerror(errno);
}

void makeRaw(int fd, speed_t speed)
{
  termios tio{};
  if (tcgetattr(fd, &tio) != 0)
    throw SerialError("tcgetattr: " + errnoText());
  cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~(CSTOPB | CRTSCTS | PARENB);
  tio.c_iflag &= ~(IXON | IXOFF | IXANY);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  if (speed != 0 && (cfsetispeed(&tio, speed) != 0 || cfsetospeed(&tio, speed) != 0))
    throw SerialError("cfsetspeed: " + errnoText());
  if (tcsetattr(fd, TCSANOW, &tio) != 0)
    throw SerialError("tcsetattr: " + errnoText());
}

/// Waits for input on fd; true when readable, false on time-out; throws on hang-up/error.
bool waitReadable(int fd, double timeout_s, const std::string& what)
{
  pollfd p{fd, POLLIN, 0};
  const int ms = timeout_s <= 0.0 ? 0 : static_cast<int>(timeout_s * 1000.0 + 0.5);
  int r;
  do
    r = ::poll(&p, 1, ms);
  while (r < 0 && errno == EINTR);
  if (r < 0)
    throw SerialError(what + ": poll: " + errnoText());
  if (r == 0)
    return false;
  if ((p.revents & POLLIN) != 0)
    return true;
  if ((p.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0)
    throw SerialError(what + ": the other end hung up (device gone)");
  return false;
}
}  // namespace

SerialPort::~SerialPort()
{
  close();
}

unsigned int SerialPort::speedConstant(int baud)
{
  switch (baud)
  {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    case 460800:
      return B460800;
    case 500000:
      return B500000;
    case 576000:
      return B576000;
    case 921600:
      return B921600;
    case 1000000:
      return B1000000;
    default:
      throw std::invalid_argument("SerialPort: baud rate " + std::to_string(baud) + " is not a termios speed");
  }
}

void SerialPort::open(const std::string& device, int baud)
{
  close();
  const speed_t speed = speedConstant(baud);
  const int fd = ::open(device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0)
    throw SerialError("cannot open serial port " + device + ": " + errnoText());
  try
  {
    makeRaw(fd, speed);
  }
  catch (const SerialError& e)
  {
    ::close(fd);
    throw SerialError("cannot configure serial port " + device + ": " + e.what());
  }
  fd_ = fd;
  device_ = device;
  tcflush(fd_, TCIOFLUSH);
}

void SerialPort::close()
{
  if (fd_ >= 0)
    ::close(fd_);
  fd_ = -1;
}

void SerialPort::write(const std::vector<uint8_t>& bytes)
{
  if (fd_ < 0)
    throw SerialError("serial port " + device_ + " is not open");
  size_t done = 0;
  while (done < bytes.size())
  {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n < 0)
    {
      if (errno == EINTR)
        continue;
      if (errno == EAGAIN)
      {
        pollfd p{fd_, POLLOUT, 0};
        if (::poll(&p, 1, 100) <= 0 || (p.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0)
          throw SerialError("serial port " + device_ + ": write stalled or device gone");
        continue;
      }
      throw SerialError("serial port " + device_ + ": write: " + errnoText());
    }
    done += static_cast<size_t>(n);
  }
}

std::vector<uint8_t> SerialPort::read(size_t max_bytes, double timeout_s)
{
  if (fd_ < 0)
    throw SerialError("serial port " + device_ + " is not open");
  std::vector<uint8_t> out;
  if (!waitReadable(fd_, timeout_s, "serial port " + device_))
    return out;
  out.resize(max_bytes);
  const ssize_t n = ::read(fd_, out.data(), max_bytes);
  if (n < 0)
  {
    if (errno == EAGAIN || errno == EINTR)
      return {};
    throw SerialError("serial port " + device_ + ": read: " + errnoText());
  }
  if (n == 0)
    throw SerialError("serial port " + device_ + ": end of file (device gone)");
  out.resize(static_cast<size_t>(n));
  return out;
}

void SerialPort::flushInput()
{
  if (fd_ >= 0)
    tcflush(fd_, TCIFLUSH);
}

PseudoTerminal::PseudoTerminal(const std::string& link_path)
{
  char name[256] = {0};
  if (::openpty(&master_, &slave_, name, nullptr, nullptr) != 0)
    throw SerialError("openpty: " + errnoText());
  slave_path_ = name;
  makeRaw(master_, 0);
  makeRaw(slave_, 0);
  ::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
  ::fcntl(master_, F_SETFD, FD_CLOEXEC);
  ::fcntl(slave_, F_SETFD, FD_CLOEXEC);
  if (!link_path.empty())
  {
    ::unlink(link_path.c_str());
    if (::symlink(slave_path_.c_str(), link_path.c_str()) != 0)
    {
      const std::string why = errnoText();
      close();
      throw SerialError("cannot link " + link_path + " to " + slave_path_ + ": " + why);
    }
    link_path_ = link_path;
  }
}

PseudoTerminal::~PseudoTerminal()
{
  close();
}

bool PseudoTerminal::write(const std::vector<uint8_t>& bytes)
{
  if (master_ < 0)
    return false;
  size_t done = 0;
  while (done < bytes.size())
  {
    const ssize_t n = ::write(master_, bytes.data() + done, bytes.size() - done);
    if (n < 0)
    {
      if (errno == EINTR)
        continue;
      if (errno == EAGAIN)
      {
        pollfd p{master_, POLLOUT, 0};
        if (::poll(&p, 1, 100) <= 0)
          return false;
        continue;
      }
      return false;
    }
    done += static_cast<size_t>(n);
  }
  return true;
}

std::vector<uint8_t> PseudoTerminal::read(size_t max_bytes, double timeout_s)
{
  std::vector<uint8_t> out;
  if (master_ < 0)
    return out;
  pollfd p{master_, POLLIN, 0};
  const int ms = timeout_s <= 0.0 ? 0 : static_cast<int>(timeout_s * 1000.0 + 0.5);
  if (::poll(&p, 1, ms) <= 0 || (p.revents & POLLIN) == 0)
    return out;
  out.resize(max_bytes);
  const ssize_t n = ::read(master_, out.data(), max_bytes);
  out.resize(n > 0 ? static_cast<size_t>(n) : 0);
  return out;
}

void PseudoTerminal::close()
{
  if (!link_path_.empty())
    ::unlink(link_path_.c_str());
  link_path_.clear();
  if (slave_ >= 0)
    ::close(slave_);
  if (master_ >= 0)
    ::close(master_);
  slave_ = master_ = -1;
}
}  // namespace biovision_common
