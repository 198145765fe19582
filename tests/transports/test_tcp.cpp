// The TCP server port on loopback: fan-out, hang-ups, client limit, commands, slow clients.

#include <arpa/inet.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "transports/byte_port.hpp"

namespace navemu::transport {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// A recognisable chunk of exactly `size` bytes: "$SEQ,000042,ABC...\r\n".
std::string make_chunk(int seq, std::size_t size) {
  std::string s = fmt::format("$SEQ,{:06d},", seq);
  while (s.size() + 2 < size) s += static_cast<char>('A' + s.size() % 26);
  return s + "\r\n";
}

std::string chunks(int first, int last, std::size_t size) {
  std::string s;
  for (int i = first; i <= last; ++i) s += make_chunk(i, size);
  return s;
}

// A non-blocking loopback client connected to `port` (IPv4, or IPv6 ::1).
int connect_client(int port, bool ipv6 = false) {
  const int fd = ::socket(ipv6 ? AF_INET6 : AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return -1;
  int rc;
  if (ipv6) {
    sockaddr_in6 a{};
    a.sin6_family = AF_INET6;
    a.sin6_port = htons(static_cast<std::uint16_t>(port));
    a.sin6_addr = in6addr_loopback;
    rc = ::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  } else {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<std::uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    rc = ::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  }
  if (rc != 0) {
    ::close(fd);
    return -1;
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
  return fd;
}

// Calls service() until cond() holds or the time limit passes.
bool service_until(BytePort& port, const std::function<bool()>& cond,
                   milliseconds limit = milliseconds(2000)) {
  const auto deadline = Clock::now() + limit;
  while (Clock::now() < deadline) {
    port.service();
    if (cond()) return true;
    std::this_thread::sleep_for(milliseconds(1));
  }
  return cond();
}

// Reads until `want` bytes or the time limit; stops early on EOF.
std::string read_n(int fd, std::size_t want, milliseconds limit = milliseconds(2000)) {
  std::string data;
  const auto deadline = Clock::now() + limit;
  char buf[16384];
  while (data.size() < want && Clock::now() < deadline) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 5) <= 0) continue;
    const ssize_t n = ::recv(fd, buf, sizeof buf, MSG_DONTWAIT);
    if (n == 0) break;
    if (n > 0) data.append(buf, static_cast<std::size_t>(n));
  }
  return data;
}

// Whatever is waiting now, without waiting.
void drain(int fd, std::string& into) {
  char buf[16384];
  for (ssize_t n; (n = ::recv(fd, buf, sizeof buf, MSG_DONTWAIT)) > 0;)
    into.append(buf, static_cast<std::size_t>(n));
}

TEST(Tcp, TwoClientsReceiveEveryChunkAndOneLeaving) {
  auto port = open_tcp_server({});
  const int p = tcp_server_port(*port);
  ASSERT_GT(p, 0);
  EXPECT_EQ(port->describe(), fmt::format("tcp 127.0.0.1:{}", p));
  const int a = connect_client(p);
  const int b = connect_client(p);
  ASSERT_GE(a, 0);
  ASSERT_GE(b, 0);
  ASSERT_TRUE(service_until(*port, [&] { return tcp_client_count(*port) == 2; }));

  for (int i = 0; i < 20; ++i) {
    ASSERT_TRUE(port->write(make_chunk(i, 200)));
    port->service();
  }
  EXPECT_EQ(read_n(a, 20 * 200), chunks(0, 19, 200));
  EXPECT_EQ(read_n(b, 20 * 200), chunks(0, 19, 200));

  // A leaves; the port notices and B carries on.
  ::close(a);
  ASSERT_TRUE(service_until(*port, [&] { return tcp_client_count(*port) == 1; }));
  for (int i = 20; i < 30; ++i) ASSERT_TRUE(port->write(make_chunk(i, 200)));
  EXPECT_EQ(read_n(b, 10 * 200), chunks(20, 29, 200));
  EXPECT_EQ(port->counters().chunks_written, 30u);
  EXPECT_EQ(port->counters().clients_connected, 2u);
  EXPECT_EQ(port->counters().errors, 0u);
  ::close(b);

  // With nobody connected a chunk is dropped and counted.
  ASSERT_TRUE(service_until(*port, [&] { return tcp_client_count(*port) == 0; }));
  EXPECT_FALSE(port->write(make_chunk(30, 200)));
  EXPECT_EQ(port->counters().chunks_dropped, 1u);
}

TEST(Tcp, ClientsOverTheLimitAreRefused) {
  auto port = open_tcp_server({"127.0.0.1", 0, 8});
  const int p = tcp_server_port(*port);
  std::vector<int> fds;
  for (int i = 0; i < 8; ++i) {
    fds.push_back(connect_client(p));
    ASSERT_GE(fds.back(), 0);
  }
  ASSERT_TRUE(service_until(*port, [&] { return tcp_client_count(*port) == 8; }));
  const int ninth = connect_client(p);  // the kernel completes the handshake; the port refuses
  ASSERT_GE(ninth, 0);
  ASSERT_TRUE(service_until(*port, [&] { return port->counters().clients_refused == 1; }));
  char c;
  const auto deadline = Clock::now() + milliseconds(2000);
  ssize_t n = -1;
  while (Clock::now() < deadline) {
    pollfd pf{ninth, POLLIN, 0};
    ::poll(&pf, 1, 5);
    n = ::recv(ninth, &c, 1, MSG_DONTWAIT);
    if (n == 0 || (n < 0 && errno != EAGAIN)) break;
  }
  EXPECT_TRUE(n == 0 || (n < 0 && errno == ECONNRESET)) << "the ninth client is closed";
  EXPECT_EQ(tcp_client_count(*port), 8);
  ASSERT_TRUE(port->write(make_chunk(0, 50)));
  for (int fd : fds) EXPECT_EQ(read_n(fd, 50), make_chunk(0, 50));
  for (int fd : fds) ::close(fd);
  ::close(ninth);
}

TEST(Tcp, CommandsFromAClientAreRead) {
  auto port = open_tcp_server({});
  const int a = connect_client(tcp_server_port(*port));
  ASSERT_GE(a, 0);
  ASSERT_TRUE(service_until(*port, [&] { return tcp_client_count(*port) == 1; }));
  const std::string cmd = "\xb5\x62\x0a\x04\x00\x00\x0e\x34";  // UBX MON-VER poll
  ASSERT_EQ(::send(a, cmd.data(), cmd.size(), 0), static_cast<ssize_t>(cmd.size()));
  std::string got;
  const auto deadline = Clock::now() + milliseconds(2000);
  std::uint8_t buf[64];
  while (got.size() < cmd.size() && Clock::now() < deadline) {
    const std::size_t n = port->read(buf);
    got.append(reinterpret_cast<const char*>(buf), n);
    if (n == 0) std::this_thread::sleep_for(milliseconds(1));
  }
  EXPECT_EQ(got, cmd);
  EXPECT_EQ(port->counters().bytes_read, cmd.size());
  // A client that sends and hangs up: its bytes are read first, then it is closed.
  ::shutdown(a, SHUT_WR);
  ASSERT_TRUE(service_until(*port, [&] {
    port->read(buf);
    return tcp_client_count(*port) == 0;
  }));
  ::close(a);
}

TEST(Tcp, AClientThatNeverReadsDoesNotHoldTheOthers) {
  auto port = open_tcp_server({});
  const int p = tcp_server_port(*port);
  const int stalled = connect_client(p);
  const int live = connect_client(p);
  ASSERT_GE(stalled, 0);
  ASSERT_GE(live, 0);
  ASSERT_TRUE(service_until(*port, [&] { return tcp_client_count(*port) == 2; }));

  const int n = 2000;  // 1.2 MB: far more than the stalled client's socket buffers hold
  std::string got;
  const auto t0 = Clock::now();
  for (int i = 0; i < n; ++i) {
    ASSERT_TRUE(port->write(make_chunk(i, 600)));
    port->service();
    drain(live, got);
  }
  const auto elapsed = Clock::now() - t0;
  EXPECT_LT(elapsed, milliseconds(3000));
  got += read_n(live, n * 600 - got.size());
  EXPECT_EQ(got.size(), static_cast<std::size_t>(n) * 600);
  EXPECT_TRUE(got == chunks(0, n - 1, 600)) << "the live client got every chunk whole";
  EXPECT_EQ(port->counters().chunks_written, static_cast<std::uint64_t>(n));
  EXPECT_GT(port->counters().client_chunks_dropped, 0u);
  EXPECT_EQ(tcp_client_count(*port), 2);

  // What the stalled client finally reads is whole chunks with a gap, never a torn one.
  // (service() meanwhile, so a tail it was owed is sent as it makes room.)
  std::string old;
  const auto hard_deadline = Clock::now() + milliseconds(3000);
  for (auto last = Clock::now();
       Clock::now() - last < milliseconds(50) && Clock::now() < hard_deadline;) {
    const std::size_t before = old.size();
    port->service();
    drain(stalled, old);
    if (old.size() != before) last = Clock::now();
    std::this_thread::sleep_for(milliseconds(1));
  }
  ASSERT_EQ(old.size() % 600, 0u);
  EXPECT_LT(old.size(), static_cast<std::size_t>(n) * 600);
  for (std::size_t off = 0; off < old.size(); off += 600)
    EXPECT_EQ(old.compare(off, 5, "$SEQ,"), 0) << off;
  ::close(stalled);
  ::close(live);
}

TEST(Tcp, Ipv6Loopback) {
  std::unique_ptr<BytePort> port;
  try {
    port = open_tcp_server({"::1", 0});
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "no IPv6 loopback here: " << e.what();
  }
  const int p = tcp_server_port(*port);
  EXPECT_EQ(port->describe(), fmt::format("tcp [::1]:{}", p));
  const int a = connect_client(p, true);
  ASSERT_GE(a, 0);
  ASSERT_TRUE(service_until(*port, [&] { return tcp_client_count(*port) == 1; }));
  ASSERT_TRUE(port->write(make_chunk(7, 80)));
  EXPECT_EQ(read_n(a, 80), make_chunk(7, 80));
  ::close(a);
}

TEST(Tcp, OpeningErrorsNameTheAddress) {
  auto first = open_tcp_server({});
  const int p = tcp_server_port(*first);
  try {
    open_tcp_server({"127.0.0.1", p});
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), fmt::format("tcp 127.0.0.1:{}: address already in use", p));
  }
  EXPECT_THROW(open_tcp_server({"localhost", 0}), std::runtime_error);  // numeric only
  EXPECT_THROW(open_tcp_server({"127.0.0.1", 70000}), std::runtime_error);
  EXPECT_EQ(tcp_server_port(*open_log_file("/dev/null")), -1);
}

}  // namespace
}  // namespace navemu::transport
