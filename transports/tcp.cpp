// TCP server port: socket(7), tcp(7), accept4(2), send(2) with MSG_NOSIGNAL, poll(2).

#include <arpa/inet.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <linux/sockios.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cctype>
#include <cerrno>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "transports/byte_port.hpp"

namespace navemu::transport {
namespace {

constexpr std::size_t kTailReserve = 16 * 1024;  // per-client pending tail, reserved once
constexpr int kMaxAcceptsPerService = 64;        // bounds the accept loop of one service()

// strerror text with a lower-case first letter, to follow "tcp 127.0.0.1:5000: ".
std::string errno_text(int e) {
  std::string s = std::error_code(e, std::generic_category()).message();
  if (!s.empty()) s[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(s[0])));
  return s;
}

// "127.0.0.1:2947" or "[::1]:2947".
std::string endpoint_text(const std::string& address, int port) {
  return address.find(':') != std::string::npos ? fmt::format("[{}]:{}", address, port)
                                                : fmt::format("{}:{}", address, port);
}

bool would_block(int e) { return e == EAGAIN || e == EWOULDBLOCK; }

class TcpServer final : public BytePort {
 public:
  explicit TcpServer(const TcpServerOptions& opt)
      : address_(opt.bind_address.empty() ? "127.0.0.1" : opt.bind_address),
        max_backlog_(opt.max_backlog_bytes) {
    const std::string what = "tcp " + endpoint_text(address_, opt.port);
    if (opt.port < 0 || opt.port > 65535) throw std::runtime_error(what + ": port out of range");
    if (opt.max_clients < 1) throw std::runtime_error(what + ": max_clients must be at least 1");

    // Numeric addresses only (getaddrinfo(3) with AI_NUMERICHOST): no DNS in a real-time tool.
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_flags = AI_PASSIVE | AI_NUMERICHOST | AI_NUMERICSERV;
    addrinfo* res = nullptr;
    const std::string port_text = std::to_string(opt.port);
    if (::getaddrinfo(address_.c_str(), port_text.c_str(), &hints, &res) != 0 || res == nullptr)
      throw std::runtime_error(what + ": not a numeric IPv4 or IPv6 address");
    listen_fd_ = ::socket(res->ai_family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (listen_fd_ < 0) {
      const int e = errno;
      ::freeaddrinfo(res);
      throw std::runtime_error(what + ": " + errno_text(e));
    }
    // SO_REUSEADDR: a restarted emulator can bind while old connections sit in TIME_WAIT.
    const int one = 1;
    ::setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    const int bound = ::bind(listen_fd_, res->ai_addr, res->ai_addrlen);
    const int bind_errno = errno;
    ::freeaddrinfo(res);
    if (bound != 0 || ::listen(listen_fd_, 16) != 0) {
      const int e = bound != 0 ? bind_errno : errno;
      ::close(listen_fd_);
      throw std::runtime_error(what + ": " + errno_text(e));
    }
    sockaddr_storage ss{};
    socklen_t len = sizeof ss;
    ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&ss), &len);
    port_ = ntohs(ss.ss_family == AF_INET6 ? reinterpret_cast<const sockaddr_in6*>(&ss)->sin6_port
                                           : reinterpret_cast<const sockaddr_in*>(&ss)->sin_port);

    clients_.resize(static_cast<std::size_t>(opt.max_clients));
    for (Client& c : clients_) c.tail.reserve(kTailReserve);
    pollfds_.resize(clients_.size());
  }

  ~TcpServer() override {
    for (Client& c : clients_) close_client(c);
    if (listen_fd_ >= 0) ::close(listen_fd_);
  }
  TcpServer(const TcpServer&) = delete;
  TcpServer& operator=(const TcpServer&) = delete;

  using BytePort::write;

  bool write(std::span<const std::uint8_t> chunk) override {
    if (chunk.empty()) return true;
    bool taken = false;
    for (Client& c : clients_) {
      if (c.fd < 0) continue;
      if (send_to(c, chunk))
        taken = true;
      else if (c.fd >= 0)
        counters_.client_chunks_dropped++;
    }
    if (!taken) {
      counters_.chunks_dropped++;
      counters_.bytes_dropped += chunk.size();
      return false;
    }
    counters_.chunks_written++;
    return true;
  }

  std::size_t read(std::span<std::uint8_t> buf) override {
    // Clients in turn, starting with the one whose bytes filled the buffer last time, so one
    // client's stream is not interleaved with another's more than necessary.
    std::size_t got = 0;
    const std::size_t n = clients_.size();
    for (std::size_t k = 0; k < n && got < buf.size(); ++k) {
      const std::size_t i = (read_next_ + k) % n;
      Client& c = clients_[i];
      if (c.fd < 0) continue;
      const ssize_t r = ::recv(c.fd, buf.data() + got, buf.size() - got, MSG_DONTWAIT);
      if (r > 0) {
        got += static_cast<std::size_t>(r);
        if (got == buf.size()) read_next_ = i;
      } else if (r == 0) {
        close_client(c);  // orderly shutdown by the client
      } else if (!would_block(errno) && errno != EINTR) {
        if (errno != ECONNRESET) counters_.errors++;
        close_client(c);
      }
    }
    counters_.bytes_read += got;
    return got;
  }

  void service() override {
    accept_clients();
    for (Client& c : clients_)
      if (c.fd >= 0) flush_tail(c);
    notice_hangups();
  }

  std::string describe() const override { return "tcp " + endpoint_text(address_, port_); }

  int port() const { return port_; }
  int client_count() const {
    int n = 0;
    for (const Client& c : clients_) n += c.fd >= 0 ? 1 : 0;
    return n;
  }

 private:
  struct Client {
    int fd = -1;
    std::vector<std::uint8_t> tail;  // unsent end of the last chunk for this client
    std::size_t tail_off = 0;
  };

  void close_client(Client& c) {
    if (c.fd < 0) return;
    ::close(c.fd);
    c.fd = -1;
    c.tail.clear();
    c.tail_off = 0;
  }

  // Accepts what is waiting; clients beyond max_clients are closed at once and counted.
  void accept_clients() {
    for (int k = 0; k < kMaxAcceptsPerService; ++k) {
      const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
      if (fd < 0) {
        if (errno == ECONNABORTED || errno == EINTR) continue;
        if (!would_block(errno)) counters_.errors++;  // EMFILE and the like
        return;
      }
      Client* slot = nullptr;
      for (Client& c : clients_)
        if (c.fd < 0) {
          slot = &c;
          break;
        }
      if (slot == nullptr) {
        ::close(fd);
        counters_.clients_refused++;
        continue;
      }
      // Epochs are small and latency matters more than packet count (tcp(7) TCP_NODELAY).
      const int one = 1;
      ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
      slot->fd = fd;
      counters_.clients_connected++;
    }
  }

  // poll(2) without waiting: errors and hang-ups close a client; a client that shut down its
  // sending side (POLLRDHUP) is closed once nothing it sent is left to read.
  void notice_hangups() {
    std::size_t n = 0;
    for (const Client& c : clients_) {
      if (c.fd < 0) continue;
      pollfds_[n++] = pollfd{c.fd, static_cast<short>(POLLRDHUP), 0};
    }
    if (n == 0 || ::poll(pollfds_.data(), n, 0) <= 0) return;
    for (std::size_t k = 0; k < n; ++k) {
      const short ev = pollfds_[k].revents;
      if (ev == 0) continue;
      for (Client& c : clients_) {
        if (c.fd != pollfds_[k].fd) continue;
        int unread = 0;
        if ((ev & (POLLERR | POLLHUP | POLLNVAL)) != 0 ||
            ((ev & POLLRDHUP) != 0 && ::ioctl(c.fd, FIONREAD, &unread) == 0 && unread == 0))
          close_client(c);
        break;
      }
    }
  }

  // Sends what is left of a partly sent chunk; true when nothing is left.
  bool flush_tail(Client& c) {
    if (c.tail_off >= c.tail.size()) return true;
    const ssize_t n = send_raw(c, c.tail.data() + c.tail_off, c.tail.size() - c.tail_off);
    if (n > 0) c.tail_off += static_cast<std::size_t>(n);
    if (c.fd < 0) return false;
    if (c.tail_off < c.tail.size()) return false;
    c.tail.clear();
    c.tail_off = 0;
    return true;
  }

  // One chunk to one client, whole or not at all; false when this client could not take it.
  bool send_to(Client& c, std::span<const std::uint8_t> chunk) {
    if (!flush_tail(c)) return false;
    // Unsent bytes in the socket (SIOCOUTQ, tcp(7)): a client that has stopped reading gets
    // no more once its backlog is over the limit.
    int queued = 0;
    if (::ioctl(c.fd, SIOCOUTQ, &queued) == 0 && queued > 0 &&
        static_cast<std::size_t>(queued) + chunk.size() > max_backlog_)
      return false;
    const ssize_t n = send_raw(c, chunk.data(), chunk.size());
    if (n <= 0) return false;
    const auto sent = static_cast<std::size_t>(n);
    if (sent < chunk.size()) {
      c.tail.assign(chunk.begin() + static_cast<std::ptrdiff_t>(sent), chunk.end());
      c.tail_off = 0;
    }
    return true;
  }

  // send(2) without blocking or SIGPIPE; a peer that went away closes the client.
  ssize_t send_raw(Client& c, const std::uint8_t* data, std::size_t size) {
    ssize_t n;
    do n = ::send(c.fd, data, size, MSG_NOSIGNAL | MSG_DONTWAIT);
    while (n < 0 && errno == EINTR);
    if (n > 0) {
      counters_.bytes_written += static_cast<std::uint64_t>(n);
    } else if (n < 0 && !would_block(errno)) {
      if (errno != EPIPE && errno != ECONNRESET) counters_.errors++;
      close_client(c);
    }
    return n;
  }

  std::string address_;
  std::size_t max_backlog_;
  int listen_fd_ = -1;
  int port_ = 0;
  std::vector<Client> clients_;  // max_clients slots; fd -1 when free
  std::vector<pollfd> pollfds_;  // scratch for notice_hangups(), sized once
  std::size_t read_next_ = 0;
};

}  // namespace

std::unique_ptr<BytePort> open_tcp_server(const TcpServerOptions& opt) {
  return std::make_unique<TcpServer>(opt);
}

int tcp_server_port(const BytePort& port) {
  const auto* tcp = dynamic_cast<const TcpServer*>(&port);
  return tcp != nullptr ? tcp->port() : -1;
}

int tcp_client_count(const BytePort& port) {
  const auto* tcp = dynamic_cast<const TcpServer*>(&port);
  return tcp != nullptr ? tcp->client_count() : 0;
}

}  // namespace navemu::transport
