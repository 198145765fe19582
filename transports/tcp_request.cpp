#include "transports/tcp_request.hpp"

#include <fmt/format.h>
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

namespace navemu::transport {

std::vector<std::string> tcp_request_lines(const std::string& address, int port, const std::vector<std::string>& lines,
                                           std::size_t expected, double timeout_s) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_NUMERICHOST | AI_NUMERICSERV;  // numeric only, as the servers bind
  addrinfo* res = nullptr;
  const std::string port_text = std::to_string(port);
  if (::getaddrinfo(address.c_str(), port_text.c_str(), &hints, &res) != 0 || res == nullptr)
    throw std::runtime_error(fmt::format("{} is not a numeric IPv4 or IPv6 address", address));
  const int fd = ::socket(res->ai_family, SOCK_STREAM | SOCK_CLOEXEC, 0);
  const bool connected = fd >= 0 && ::connect(fd, res->ai_addr, res->ai_addrlen) == 0;
  const int err = errno;
  ::freeaddrinfo(res);
  if (!connected) {
    if (fd >= 0) ::close(fd);
    throw std::runtime_error(fmt::format("cannot connect to {}:{} ({})", address, port, std::strerror(err)));
  }
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  for (std::size_t sent = 0; sent < out.size();) {
    const ssize_t n = ::send(fd, out.data() + sent, out.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;
    sent += static_cast<std::size_t>(n);
  }
  std::vector<std::string> replies;
  std::string in;
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (replies.size() < expected) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) break;
    char buf[4096];
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) break;
    in.append(buf, static_cast<std::size_t>(n));
    for (std::size_t nl; (nl = in.find('\n')) != std::string::npos;) {
      replies.push_back(in.substr(0, nl));
      in.erase(0, nl + 1);
    }
  }
  ::close(fd);
  return replies;
}

}  // namespace navemu::transport
