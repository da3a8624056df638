#include <gtest/gtest.h>

#include <unistd.h>

#include "biovision_common/serial_port.hpp"

using biovision_common::PseudoTerminal;
using biovision_common::SerialError;
using biovision_common::SerialPort;

TEST(SerialPort, BytesCrossAPseudoTerminalBothWays)
{
  PseudoTerminal pty;
  SerialPort port;
  port.open(pty.slavePath(), 115200);
  port.write({0xFA, 0xFB, 0x03, 0x00, 0x00, 0x00});
  std::vector<uint8_t> got;
  for (int i = 0; i < 10 && got.size() < 6; ++i)
  {
    auto part = pty.read(64, 0.1);
    got.insert(got.end(), part.begin(), part.end());
  }
  EXPECT_EQ(got, (std::vector<uint8_t>{0xFA, 0xFB, 0x03, 0x00, 0x00, 0x00}));
  ASSERT_TRUE(pty.write({0x01, 0x02}));
  std::vector<uint8_t> back;
  for (int i = 0; i < 10 && back.size() < 2; ++i)
  {
    auto part = port.read(64, 0.1);
    back.insert(back.end(), part.begin(), part.end());
  }
  EXPECT_EQ(back, (std::vector<uint8_t>{0x01, 0x02}));
  EXPECT_TRUE(port.read(64, 0.02).empty()) << "a time-out is an empty read, not an error";
}

TEST(SerialPort, AClosedPeerIsAnErrorNotATimeOut)
{
  PseudoTerminal pty;
  SerialPort port;
  port.open(pty.slavePath(), 9600);
  pty.close();
  EXPECT_THROW(port.read(64, 0.2), SerialError);
}

TEST(SerialPort, AMissingDeviceAndABadBaudRateAreNamed)
{
  SerialPort port;
  try
  {
    port.open("/nonexistent/ttyUSB9", 9600);
    FAIL() << "opened a missing device";
  }
  catch (const SerialError& e)
  {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/ttyUSB9"), std::string::npos) << e.what();
  }
  EXPECT_THROW(SerialPort::speedConstant(12345), std::invalid_argument);
}

TEST(PseudoTerminal, TheLinkNamesTheSlaveAndGoesAwayOnClose)
{
  const std::string link = "/tmp/biovision_test_pty_link_" + std::to_string(::getpid());
  {
    PseudoTerminal pty(link);
    char target[256] = {0};
    ASSERT_GT(::readlink(link.c_str(), target, sizeof(target) - 1), 0);
    EXPECT_EQ(pty.slavePath(), std::string(target));
  }
  EXPECT_NE(::access(link.c_str(), F_OK), 0);
}
