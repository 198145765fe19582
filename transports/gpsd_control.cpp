// gpsd's control socket: a Unix-domain stream socket taking one command per line and answering
// each with a line "OK" or "ERROR" (gpsd(8), "GPS DEVICE MANAGEMENT"; gpsdctl(8) is gpsd's own
// client of it).

#include "transports/gpsd_control.hpp"

#include <fmt/format.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

namespace navemu::transport {

std::string gpsd_control(const std::string& socket_path, const std::string& command,
                         std::chrono::milliseconds timeout) {
  const auto fail = [&](const std::string& why) {
    return std::runtime_error(fmt::format("gpsd control socket {}: {}", socket_path, why));
  };
  const auto os_error = [](int e) { return std::error_code(e, std::generic_category()).message(); };
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (socket_path.size() >= sizeof addr.sun_path) throw fail("path too long");
  std::memcpy(addr.sun_path, socket_path.c_str(), socket_path.size() + 1);

  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw fail(os_error(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0)
    throw fail(os_error(errno));
  const std::string line = command + "\n";
  if (::send(fd, line.data(), line.size(), MSG_NOSIGNAL) != static_cast<ssize_t>(line.size()))
    throw fail(fmt::format("sending: {}", os_error(errno)));
  if (timeout.count() <= 0) return {};

  // The answer: one line, read until its newline, gpsd closing, or the deadline.
  std::string answer;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (answer.find('\n') == std::string::npos) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) throw fail(fmt::format("no answer to '{}'", command));
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
    char buf[64];
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    answer.append(buf, static_cast<std::size_t>(n));
  }
  answer = answer.substr(0, answer.find_first_of("\r\n"));
  if (answer.empty()) throw fail(fmt::format("no answer to '{}'", command));
  return answer;
}

}  // namespace navemu::transport
