// UDP sender port and receiver: udp(7), sendto(2), recv(2) with MSG_TRUNC.

#include <arpa/inet.h>
#include <fmt/format.h>
#include <netdb.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "transports/byte_port.hpp"

namespace navemu::transport {
namespace {

// strerror text with a lower-case first letter, to follow "udp 127.0.0.1:5000: ".
std::string errno_text(int e) {
  std::string s = std::error_code(e, std::generic_category()).message();
  if (!s.empty()) s[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(s[0])));
  return s;
}

// "127.0.0.1:5000" or "[::1]:5000".
std::string endpoint_text(const std::string& address, int port) {
  return address.find(':') != std::string::npos ? fmt::format("[{}]:{}", address, port)
                                                : fmt::format("{}:{}", address, port);
}

// A socket address from a numeric host and port (getaddrinfo(3), AI_NUMERICHOST: no DNS).
struct Endpoint {
  sockaddr_storage addr{};
  socklen_t len = 0;
  int family = AF_UNSPEC;
};

Endpoint resolve(const std::string& address, int port, bool passive, const std::string& what) {
  if (port < 0 || port > 65535) throw std::runtime_error(what + ": port out of range");
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_DGRAM;
  hints.ai_flags = AI_NUMERICHOST | AI_NUMERICSERV | (passive ? AI_PASSIVE : 0);
  addrinfo* res = nullptr;
  const std::string port_text = std::to_string(port);
  if (::getaddrinfo(address.c_str(), port_text.c_str(), &hints, &res) != 0 || res == nullptr)
    throw std::runtime_error(what + ": not a numeric IPv4 or IPv6 address");
  Endpoint ep;
  std::memcpy(&ep.addr, res->ai_addr, res->ai_addrlen);
  ep.len = res->ai_addrlen;
  ep.family = res->ai_family;
  ::freeaddrinfo(res);
  return ep;
}

class UdpSender final : public BytePort {
 public:
  explicit UdpSender(const UdpSenderOptions& opt)
      : text_("udp " + endpoint_text(opt.address, opt.port)) {
    if (opt.port == 0) throw std::runtime_error(text_ + ": port 0 is not a destination");
    dest_ = resolve(opt.address, opt.port, false, text_);
    fd_ = ::socket(dest_.family, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd_ < 0) throw std::runtime_error(text_ + ": " + errno_text(errno));
  }
  ~UdpSender() override { ::close(fd_); }
  UdpSender(const UdpSender&) = delete;
  UdpSender& operator=(const UdpSender&) = delete;

  using BytePort::write;

  // One datagram per chunk. The socket is not connected, so ICMP "port unreachable" from a
  // destination nobody listens on is not reported back as an error on later sends.
  bool write(std::span<const std::uint8_t> chunk) override {
    if (chunk.empty()) return true;
    ssize_t n;
    do
      n = ::sendto(fd_, chunk.data(), chunk.size(), MSG_DONTWAIT | MSG_NOSIGNAL,
                   reinterpret_cast<const sockaddr*>(&dest_.addr), dest_.len);
    while (n < 0 && errno == EINTR);
    if (n == static_cast<ssize_t>(chunk.size())) {
      counters_.chunks_written++;
      counters_.bytes_written += chunk.size();
      return true;
    }
    // EAGAIN/ENOBUFS: the send buffer is full, which is only a drop; anything else (EMSGSIZE
    // for a chunk over 65507 bytes, ENETUNREACH) is an error as well.
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != ENOBUFS) counters_.errors++;
    counters_.chunks_dropped++;
    counters_.bytes_dropped += chunk.size();
    return false;
  }

  // A UDP stream carries no commands.
  std::size_t read(std::span<std::uint8_t>) override { return 0; }

  std::string describe() const override { return text_; }

 private:
  std::string text_;
  Endpoint dest_;
  int fd_ = -1;
};

}  // namespace

std::unique_ptr<BytePort> open_udp_sender(const UdpSenderOptions& opt) {
  return std::make_unique<UdpSender>(opt);
}

UdpReceiver::UdpReceiver(const std::string& bind_address, int port) {
  const std::string address = bind_address.empty() ? "127.0.0.1" : bind_address;
  const std::string what = "udp " + endpoint_text(address, port);
  const Endpoint ep = resolve(address, port, true, what);
  const int fd = ::socket(ep.family, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) throw std::runtime_error(what + ": " + errno_text(errno));
  // A deeper queue for bursts (the kernel caps it at net.core.rmem_max), and the count of
  // datagrams the kernel dropped because the queue was full anyway (socket(7) SO_RXQ_OVFL).
  const int rcvbuf_bytes = 4 << 20, on = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf_bytes, sizeof rcvbuf_bytes);
  ::setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&ep.addr), ep.len) != 0) {
    const int e = errno;
    ::close(fd);
    throw std::runtime_error(what + ": " + errno_text(e));
  }
  // Port 0 asked the kernel for a free port: report the one it chose.
  sockaddr_storage ss{};
  socklen_t len = sizeof ss;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&ss), &len);
  port_ = ntohs(ss.ss_family == AF_INET6 ? reinterpret_cast<const sockaddr_in6*>(&ss)->sin6_port
                                         : reinterpret_cast<const sockaddr_in*>(&ss)->sin_port);
  fd_ = fd;
}

UdpReceiver::~UdpReceiver() {
  if (fd_ >= 0) ::close(fd_);
}

std::size_t UdpReceiver::receive(std::span<std::uint8_t> buf) {
  // MSG_TRUNC makes recv(2) return a datagram's real length even when it did not fit, which
  // is how truncation is noticed; truncated and empty datagrams are skipped (bounded, so a
  // flood of them cannot hold the caller).
  for (int k = 0; k < 64; ++k) {
    iovec iov{buf.data(), buf.size()};
    alignas(cmsghdr) std::array<char, CMSG_SPACE(sizeof(std::uint32_t))> control;
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control.data();
    msg.msg_controllen = control.size();
    const ssize_t n = ::recvmsg(fd_, &msg, MSG_DONTWAIT | MSG_TRUNC);
    if (n < 0) return 0;  // EAGAIN: nothing waiting (errors on a UDP socket are transient)
    // SO_RXQ_OVFL: the socket's drop count so far, on datagrams that follow a drop.
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c != nullptr; c = CMSG_NXTHDR(&msg, c))
      if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_RXQ_OVFL) {
        std::uint32_t dropped = 0;
        std::memcpy(&dropped, CMSG_DATA(c), sizeof dropped);
        kernel_dropped_ = dropped;
      }
    if (static_cast<std::size_t>(n) > buf.size()) {
      truncated_++;
      continue;
    }
    if (n > 0) return static_cast<std::size_t>(n);
  }
  return 0;
}

bool is_loopback_address(const std::string& address) {
  if (address.empty() || address == "localhost") return true;
  in_addr v4{};
  if (::inet_pton(AF_INET, address.c_str(), &v4) == 1) return (ntohl(v4.s_addr) >> 24) == 127;
  in6_addr v6{};
  if (::inet_pton(AF_INET6, address.c_str(), &v6) != 1) return false;
  if (IN6_IS_ADDR_LOOPBACK(&v6)) return true;
  return IN6_IS_ADDR_V4MAPPED(&v6) && v6.s6_addr[12] == 127;
}

}  // namespace navemu::transport
