// SocketCAN raw socket port: Linux Documentation/networking/can.rst (CAN_RAW sockets, section
// "RAW protocol sockets with can_filters"; CAN FD: "RAW socket option CAN_RAW_FD_FRAMES"),
// netdevice(7) for the interface checks (SIOCGIFINDEX, SIOCGIFHWADDR, SIOCGIFFLAGS,
// SIOCGIFMTU).

#include <fcntl.h>
#include <fmt/format.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <net/if_arp.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/uio.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "transports/can_port.hpp"
#include "transports/can_util.hpp"

namespace navemu::transport {
namespace {

std::string errno_text(int e) { return std::error_code(e, std::generic_category()).message(); }

class SocketCanPort final : public FramePort {
 public:
  static constexpr std::size_t kMaxBurst = 8;
  explicit SocketCanPort(const SocketCanOptions& opt) : name_(opt.interface), fd_frames_(opt.fd) {
    const std::string& n = name_;
    // Kernels without SocketCAN have no AF_CAN (EAFNOSUPPORT); with can.ko but no can-raw.ko
    // the protocol is missing (EPROTONOSUPPORT).
    sock_ = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
    if (sock_ < 0) {
      const int e = errno;
      if (e == EAFNOSUPPORT || e == EPROTONOSUPPORT)
        throw std::runtime_error(fmt::format(
            "socketcan {}: this kernel has no SocketCAN (socket(AF_CAN): {})", n, errno_text(e)));
      throw std::runtime_error(fmt::format("socketcan {}: socket(AF_CAN): {}", n, errno_text(e)));
    }
    try {
      setup();
    } catch (...) {
      ::close(sock_);
      throw;
    }
  }

  ~SocketCanPort() override { ::close(sock_); }
  SocketCanPort(const SocketCanPort&) = delete;
  SocketCanPort& operator=(const SocketCanPort&) = delete;

  bool write(const CanFrameView& frame, std::int64_t unix_time_ns) override {
    return write_burst(std::span<const CanFrameView>(&frame, 1), unix_time_ns) == 1;
  }

  // The frames go to the kernel in one sendmmsg(2) call: one system call per IMU sample
  // rather than one per frame (which is what limits a 1 kHz IMU inside user-mode Linux).
  std::size_t write_burst(std::span<const CanFrameView> frames, std::int64_t unix_time_ns) override {
    if (frames.size() > kMaxBurst) {  // in slices (a sample has at most five frames)
      std::size_t sent = 0;
      for (std::size_t i = 0; i < frames.size(); i += kMaxBurst)
        sent += write_burst(frames.subspan(i, std::min(kMaxBurst, frames.size() - i)), unix_time_ns);
      return sent;
    }
    std::array<canfd_frame, kMaxBurst> structs{};
    std::array<iovec, kMaxBurst> iov{};
    std::array<mmsghdr, kMaxBurst> msgs{};
    std::size_t n = 0;
    for (const CanFrameView& frame : frames) {
      if (!valid_can_frame(frame)) {
        counters_.frames_failed++;
        continue;
      }
      if (frame.fd && !fd_frames_) {
        counters_.frames_dropped++;
        continue;
      }
      // A classic frame is struct can_frame (CAN_MTU bytes), the first CAN_MTU bytes of a
      // canfd_frame with flags 0; a CAN FD frame is canfd_frame (CANFD_MTU bytes). The size
      // tells the kernel which it is.
      canfd_frame& f = structs[n];
      f.can_id = frame.error ? (frame.id | CAN_ERR_FLAG) : frame.extended ? (frame.id | CAN_EFF_FLAG) : frame.id;
      f.len = static_cast<std::uint8_t>(frame.data.size());
      f.flags = frame.fd && frame.brs ? CANFD_BRS : 0;
      std::memcpy(f.data, frame.data.data(), frame.data.size());
      iov[n] = {&f, frame.fd ? CANFD_MTU : CAN_MTU};
      msgs[n].msg_hdr.msg_iov = &iov[n];
      msgs[n].msg_hdr.msg_iovlen = 1;
      ++n;
    }
    if (n == 0) return 0;
    int sent;
    do sent = ::sendmmsg(sock_, msgs.data(), static_cast<unsigned>(n), 0);
    while (sent < 0 && errno == EINTR);
    const std::size_t ok = sent > 0 ? static_cast<std::size_t>(sent) : 0;
    counters_.frames_written += ok;
    if (ok > 0 && failing_) {
      failing_ = false;
      std::fputs(fmt::format("navemu: socketcan {}: sending again\n", name_).c_str(), stderr);
    }
    if (ok < n) {
      // The first unsent frame failed (sendmmsg reports its errno only when none was sent).
      // ENOBUFS: the interface's transmit queue is full; EAGAIN: the socket send buffer is.
      const bool full = sent > 0 || errno == ENOBUFS || errno == EAGAIN || errno == EWOULDBLOCK;
      if (full) {
        counters_.frames_dropped += n - ok;
      } else {  // ENETDOWN and the like: said once, until frames go out again
        counters_.frames_failed += n - ok;
        counters_.errors++;
        if (!failing_)
          std::fputs(fmt::format("navemu: socketcan {}: {}; frames fail until it is back\n", name_,
                                 errno_text(errno))
                         .c_str(),
                     stderr);
        failing_ = true;
      }
    }
    return ok;
  }

  // Reads the error frames the interface reported (the only frames this socket receives).
  void service() override {
    canfd_frame f{};
    for (int i = 0; i < 64; ++i) {
      const ssize_t n = ::read(sock_, &f, sizeof f);
      if (n < 0) {
        if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) counters_.errors++;
        return;
      }
      if (n >= static_cast<ssize_t>(CAN_MTU) && (f.can_id & CAN_ERR_FLAG) != 0)
        counters_.bus_errors++;
    }
  }

  std::string describe() const override {
    return "socketcan " + name_ + (fd_frames_ ? " (CAN FD)" : "");
  }
  bool fd_capable() const override { return fd_frames_; }
  bool carries_error_frames() const override { return true; }

 private:
  // Checks the interface, sets the socket options and binds (can.rst, "RAW protocol sockets").
  void setup() {
    const std::string& n = name_;
    if (n.empty() || n.size() >= IFNAMSIZ)
      throw std::runtime_error(fmt::format("socketcan {}: no such interface", n));
    ifreq ifr{};
    std::memcpy(ifr.ifr_name, n.c_str(), n.size() + 1);
    if (::ioctl(sock_, SIOCGIFINDEX, &ifr) != 0) {
      if (errno == ENODEV)
        throw std::runtime_error(fmt::format("socketcan {}: no such interface", n));
      throw std::runtime_error(fmt::format("socketcan {}: SIOCGIFINDEX: {}", n, errno_text(errno)));
    }
    const int index = ifr.ifr_ifindex;
    if (::ioctl(sock_, SIOCGIFHWADDR, &ifr) != 0 || ifr.ifr_hwaddr.sa_family != ARPHRD_CAN)
      throw std::runtime_error(fmt::format("socketcan {}: {} is not a CAN interface", n, n));
    if (::ioctl(sock_, SIOCGIFFLAGS, &ifr) != 0)
      throw std::runtime_error(fmt::format("socketcan {}: SIOCGIFFLAGS: {}", n, errno_text(errno)));
    if ((ifr.ifr_flags & IFF_UP) == 0)
      throw std::runtime_error(
          fmt::format("socketcan {}: interface is down (ip link set {} up)", n, n));
    if (fd_frames_) {
      // CAN FD needs an MTU of CANFD_MTU (72); CAN XL interfaces (bigger MTU) carry FD too.
      if (::ioctl(sock_, SIOCGIFMTU, &ifr) != 0)
        throw std::runtime_error(fmt::format("socketcan {}: SIOCGIFMTU: {}", n, errno_text(errno)));
      if (ifr.ifr_mtu < static_cast<int>(CANFD_MTU))
        throw std::runtime_error(
            fmt::format("socketcan {}: {} does not carry CAN FD frames (MTU {}; ip link set {} mtu "
                        "{})",
                        n, n, ifr.ifr_mtu, n, CANFD_MTU));
      const int on = 1;
      if (::setsockopt(sock_, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &on, sizeof on) != 0)
        throw std::runtime_error(
            fmt::format("socketcan {}: CAN_RAW_FD_FRAMES: {}", n, errno_text(errno)));
    }
    // Receive no data frames (empty filter list), but every error frame class.
    if (::setsockopt(sock_, SOL_CAN_RAW, CAN_RAW_FILTER, nullptr, 0) != 0)
      throw std::runtime_error(
          fmt::format("socketcan {}: CAN_RAW_FILTER: {}", n, errno_text(errno)));
    const can_err_mask_t err_mask = CAN_ERR_MASK;
    if (::setsockopt(sock_, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &err_mask, sizeof err_mask) != 0)
      throw std::runtime_error(
          fmt::format("socketcan {}: CAN_RAW_ERR_FILTER: {}", n, errno_text(errno)));
    sockaddr_can addr{};
    addr.can_family = AF_CAN;
    addr.can_ifindex = index;
    if (::bind(sock_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0)
      throw std::runtime_error(fmt::format("socketcan {}: bind: {}", n, errno_text(errno)));
  }

  std::string name_;
  bool fd_frames_;
  bool failing_ = false;  // the last send failed with an error (said on stderr)
  int sock_ = -1;
};

}  // namespace

std::unique_ptr<FramePort> open_socketcan(const SocketCanOptions& opt) {
  return std::make_unique<SocketCanPort>(opt);
}

bool socketcan_available() {
  const int s = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  if (s < 0) return false;
  ::close(s);
  return true;
}

}  // namespace navemu::transport
