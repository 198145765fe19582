// The serial port's opening errors. libserialport 0.1.1 finds devices through
// /sys/class/tty, so a pty slave cannot stand in for a serial device: only the error paths
// are tested here (real traffic needs a real or USB serial device: NAVEMU_TEST_SERIAL).

#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "transports/byte_port.hpp"

namespace navemu::transport {
namespace {

std::string open_error(const std::string& device) {
  try {
    open_serial({device, 9600});
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Serial, MissingDeviceIsNamed) {
  struct stat st {};
  if (::stat("/dev/ttyUSB9", &st) == 0) GTEST_SKIP() << "/dev/ttyUSB9 exists here";
  EXPECT_EQ(open_error("/dev/ttyUSB9"), "serial port /dev/ttyUSB9: no such device");
}

TEST(Serial, PtySlaveAndPlainFileAreNotSerialDevices) {
  auto pty = open_pty({});
  const std::string slave = pty_slave_path(*pty);
  const std::string err = open_error(slave);
  EXPECT_EQ(err.rfind("serial port " + slave + ": not a serial device", 0), 0u) << err;

  const auto file = std::filesystem::temp_directory_path() / "navemu-serial-not-a-device";
  std::ofstream(file) << "x";
  const std::string err2 = open_error(file.string());
  EXPECT_EQ(err2.rfind("serial port " + file.string() + ": not a serial device", 0), 0u) << err2;
  std::filesystem::remove(file);
}

// The text of this process's /proc/self/comm (its program name, at most 15 characters).
std::string own_program_name() {
  std::ifstream in("/proc/self/comm");
  std::string name;
  std::getline(in, name);
  return name;
}

// One owner per device: a device another open file holds an exclusive flock(2) on is refused
// before libserialport touches it, naming the holder (here this process, through a pty slave:
// libserialport would refuse a pty anyway, but only after the lock check).
TEST(Serial, DeviceLockedByAnotherOwnerIsRefusedNamingIt) {
  auto pty = open_pty({});
  const std::string slave = pty_slave_path(*pty);
  const int holder = ::open(slave.c_str(), O_RDONLY | O_NOCTTY | O_CLOEXEC);
  ASSERT_GE(holder, 0);
  ASSERT_EQ(::flock(holder, LOCK_EX | LOCK_NB), 0);
  EXPECT_EQ(open_error(slave), fmt::format("serial port {} is in use by {} (pid {})", slave,
                                           own_program_name(), ::getpid()));
  ::close(holder);
  const std::string err = open_error(slave);
  EXPECT_EQ(err.rfind("serial port " + slave + ": not a serial device", 0), 0u) << err;
}

// On a real serial device (NAVEMU_TEST_SERIAL=/dev/ttyUSB0; none here: libserialport finds
// devices through /sys/class/tty, and the only UART of these machines is the VM's console): a
// second port on the device is refused while the first is open, and other programs' opens fail
// with EBUSY (TIOCEXCL) unless they run as root.
TEST(Serial, SecondOpenOfARealDeviceIsRefused) {
  const char* device = std::getenv("NAVEMU_TEST_SERIAL");
  if (device == nullptr)
    GTEST_SKIP() << "set NAVEMU_TEST_SERIAL to a serial device (e.g. /dev/ttyUSB0) to run this";
  auto first = open_serial({device, 9600});
  EXPECT_EQ(open_error(device), fmt::format("serial port {} is in use by {} (pid {})", device,
                                            own_program_name(), ::getpid()));
  if (::geteuid() != 0) {
    errno = 0;
    EXPECT_LT(::open(device, O_RDONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC), 0);
    EXPECT_EQ(errno, EBUSY);
  }
  first.reset();
  auto again = open_serial({device, 9600});
  EXPECT_NE(again, nullptr);
}

TEST(Serial, BadBaudRateIsRefused) {
  EXPECT_NE(open_error("/dev/ttyUSB9").find("serial port"), std::string::npos);
  try {
    open_serial({"/dev/null", 0});
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad baud rate"), std::string::npos) << e.what();
  }
}

TEST(Serial, BaudChangeNeedsASerialPort) {
  auto pty = open_pty({});
  EXPECT_FALSE(set_serial_baud(*pty, 115200));
}

}  // namespace
}  // namespace navemu::transport
