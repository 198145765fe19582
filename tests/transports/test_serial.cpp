// The serial port's opening errors. libserialport 0.1.1 finds devices through
// /sys/class/tty, so a pty slave cannot stand in for a serial device: only the error paths
// are tested here (real traffic needs a real or USB serial device).

#include <gtest/gtest.h>
#include <sys/stat.h>

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
