// The SocketCAN port on a real (virtual) CAN interface: frames arrive bit for bit at another
// raw socket; opening errors name the interface. Needs a kernel with SocketCAN and vcan0 up
// (tools/run-in-uml provides one); every test skips with a message otherwise.

#include <gtest/gtest.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "transports/can_port.hpp"

namespace navemu::transport {
namespace {

// Why these tests cannot run here; empty when they can.
std::string why_no_vcan0() {
  if (!socketcan_available()) return "this kernel has no SocketCAN (run under tools/run-in-uml)";
  if (::if_nametoindex("vcan0") == 0) return "no vcan0 interface (ip link add dev vcan0 type vcan)";
  return {};
}

CanFrameView frame(std::uint32_t id, const std::vector<std::uint8_t>& data, bool extended = false,
                   bool fd = false, bool brs = false) {
  return CanFrameView{id, extended, fd, brs, data};
}

std::vector<std::uint8_t> counting_bytes(std::size_t n) {
  std::vector<std::uint8_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<std::uint8_t>(0xA0 + i);
  return v;
}

int interface_mtu(const char* name) {
  const int s = ::socket(AF_CAN, SOCK_RAW, CAN_RAW);
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, name, IFNAMSIZ - 1);
  const int rc = ::ioctl(s, SIOCGIFMTU, &ifr);
  ::close(s);
  return rc == 0 ? ifr.ifr_mtu : -1;
}

// A raw CAN socket on vcan0 that receives everything, CAN FD frames included.
struct Listener {
  int fd = -1;
  Listener() {
    fd = ::socket(AF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
    if (fd < 0) throw std::runtime_error("socket(AF_CAN)");
    const int on = 1;
    ::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &on, sizeof on);
    sockaddr_can addr{};
    addr.can_family = AF_CAN;
    addr.can_ifindex = static_cast<int>(::if_nametoindex("vcan0"));
    if (::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0)
      throw std::runtime_error("bind vcan0");
  }
  ~Listener() { ::close(fd); }

  // The next frame and the size read (CAN_MTU or CANFD_MTU); size 0 when none came in time.
  std::size_t next(canfd_frame& f, int timeout_ms = 1000) const {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, timeout_ms) <= 0) return 0;
    const ssize_t n = ::read(fd, &f, sizeof f);
    return n > 0 ? static_cast<std::size_t>(n) : 0;
  }
};

// Checks that `sent` arrived as `got` (read with size `size`).
void expect_same(const CanFrameView& sent, const canfd_frame& got, std::size_t size) {
  EXPECT_EQ(size, sent.fd ? CANFD_MTU : CAN_MTU);
  EXPECT_EQ((got.can_id & CAN_EFF_FLAG) != 0, sent.extended);
  EXPECT_EQ(got.can_id & (sent.extended ? CAN_EFF_MASK : CAN_SFF_MASK), sent.id);
  EXPECT_EQ(got.can_id & (CAN_RTR_FLAG | CAN_ERR_FLAG), 0u);
  ASSERT_EQ(got.len, sent.data.size());
  EXPECT_EQ(std::memcmp(got.data, sent.data.data(), sent.data.size()), 0);
  if (sent.fd) {
    EXPECT_EQ((got.flags & CANFD_BRS) != 0, sent.brs);
  }
}

std::string open_error(const SocketCanOptions& opt) {
  try {
    open_socketcan(opt);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(opened)";
}

TEST(SocketCanVcan, ClassicFramesArriveIdentically) {
  if (const std::string why = why_no_vcan0(); !why.empty()) GTEST_SKIP() << why;
  Listener listener;
  auto port = open_socketcan({"vcan0", false});
  EXPECT_EQ(port->describe(), "socketcan vcan0");
  EXPECT_FALSE(port->fd_capable());
  const std::vector<std::uint8_t> d4 = {0xDE, 0xAD, 0xBE, 0xEF};
  const std::vector<std::uint8_t> d8 = counting_bytes(8);
  const std::vector<CanFrameView> frames = {frame(0x123, d4), frame(0x18F02A80, d8, true),
                                            frame(0x7FF, {}), frame(0x0, d8, true)};
  for (const auto& f : frames) ASSERT_TRUE(port->write(f, 0));
  for (const auto& f : frames) {
    canfd_frame got{};
    const std::size_t size = listener.next(got);
    ASSERT_GT(size, 0u) << "frame missing";
    expect_same(f, got, size);
  }
  EXPECT_EQ(port->counters().frames_written, frames.size());

  // A CAN FD frame on a classic port is dropped; a frame with a bad length is an error.
  EXPECT_FALSE(port->write(frame(0x123, d4, false, true), 0));
  EXPECT_EQ(port->counters().frames_dropped, 1u);
  const std::vector<std::uint8_t> d9 = counting_bytes(9);
  EXPECT_FALSE(port->write(frame(0x123, d9), 0));
  EXPECT_FALSE(port->write(frame(0x800, d4), 0));
  EXPECT_EQ(port->counters().frames_failed, 2u);
  canfd_frame none{};
  EXPECT_EQ(listener.next(none, 100), 0u) << "a dropped frame went out";
  port->service();
  EXPECT_EQ(port->counters().bus_errors, 0u);
}

TEST(SocketCanVcan, FdFramesArriveIdentically) {
  if (const std::string why = why_no_vcan0(); !why.empty()) GTEST_SKIP() << why;
  if (interface_mtu("vcan0") < static_cast<int>(CANFD_MTU))
    GTEST_SKIP() << "vcan0 does not carry CAN FD (ip link set vcan0 mtu 72)";
  Listener listener;
  auto port = open_socketcan({"vcan0", true});
  EXPECT_EQ(port->describe(), "socketcan vcan0 (CAN FD)");
  EXPECT_TRUE(port->fd_capable());
  const std::vector<std::uint8_t> d64 = counting_bytes(64);
  const std::vector<std::uint8_t> d12 = counting_bytes(12);
  const std::vector<std::uint8_t> d3 = counting_bytes(3);
  const std::vector<CanFrameView> frames = {
      frame(0x510, d64, false, true, true), frame(0x1ABCDEF, d12, true, true, false),
      frame(0x123, d3),  // classic frames still go as classic frames
      frame(0x7FF, d3, false, true, true)};
  for (const auto& f : frames) ASSERT_TRUE(port->write(f, 0));
  for (const auto& f : frames) {
    canfd_frame got{};
    const std::size_t size = listener.next(got);
    ASSERT_GT(size, 0u) << "frame missing";
    expect_same(f, got, size);
  }
  const std::vector<std::uint8_t> d10 = counting_bytes(10);
  EXPECT_FALSE(port->write(frame(0x123, d10, false, true), 0));
  EXPECT_EQ(port->counters().frames_failed, 1u);
  EXPECT_EQ(port->counters().frames_written, frames.size());
}

TEST(SocketCanVcan, MissingInterfaceIsNamed) {
  if (const std::string why = why_no_vcan0(); !why.empty()) GTEST_SKIP() << why;
  EXPECT_EQ(open_error({"nosuchcan7", false}), "socketcan nosuchcan7: no such interface");
}

TEST(SocketCanVcan, NonCanInterfaceIsRefused) {
  if (const std::string why = why_no_vcan0(); !why.empty()) GTEST_SKIP() << why;
  if (::if_nametoindex("lo") == 0) GTEST_SKIP() << "no lo interface";
  EXPECT_EQ(open_error({"lo", false}), "socketcan lo: lo is not a CAN interface");
}

// vcan1, created for one test and deleted after it.
struct ScratchVcan {
  bool created = false;
  ScratchVcan() {
    if (std::system("ip link del dev vcan1 2>/dev/null") == 0) {
      // a vcan1 left over from an earlier run
    }
    created = std::system("ip link add dev vcan1 type vcan") == 0;
  }
  ~ScratchVcan() {
    if (created && std::system("ip link del dev vcan1") != 0) ADD_FAILURE() << "vcan1 left behind";
  }
};

TEST(SocketCanVcan, InterfaceDownAndWrongMtuAreNamed) {
  if (const std::string why = why_no_vcan0(); !why.empty()) GTEST_SKIP() << why;
  ScratchVcan vcan1;
  if (!vcan1.created) GTEST_SKIP() << "cannot create vcan1 (ip link add needs CAP_NET_ADMIN)";
  EXPECT_EQ(open_error({"vcan1", false}),
            "socketcan vcan1: interface is down (ip link set vcan1 up)");
  ASSERT_EQ(std::system("ip link set dev vcan1 mtu 16 && ip link set dev vcan1 up"), 0);
  EXPECT_EQ(open_error({"vcan1", true}),
            "socketcan vcan1: vcan1 does not carry CAN FD frames (MTU 16; ip link set vcan1 mtu "
            "72)");
  EXPECT_EQ(open_error({"vcan1", false}), "(opened)");  // classic frames are fine
}

}  // namespace
}  // namespace navemu::transport
