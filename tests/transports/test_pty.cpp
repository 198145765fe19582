// The pty port: raw mode, permissions, symlink handling and its lock, reopening clients, stale
// output.

#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <mutex>
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

// Splits a stream into chunks made by make_chunk(); false when anything is torn or foreign.
bool parse_chunks(const std::string& stream, std::vector<int>& seqs) {
  std::size_t pos = 0;
  while (pos < stream.size()) {
    const std::size_t end = stream.find("\r\n", pos);
    if (end == std::string::npos) return false;
    const std::string piece = stream.substr(pos, end + 2 - pos);
    if (piece.size() < 13 || piece.compare(0, 5, "$SEQ,") != 0) return false;
    const int seq = std::atoi(piece.substr(5, 6).c_str());
    if (piece != make_chunk(seq, piece.size())) return false;
    seqs.push_back(seq);
    pos = end + 2;
  }
  return true;
}

// Reads a client fd until done(data) or the time limit; never blocks longer than 5 ms a round.
std::string read_until(int fd, const std::function<bool(const std::string&)>& done,
                       milliseconds limit = milliseconds(2000)) {
  std::string data;
  const auto deadline = Clock::now() + limit;
  char buf[8192];
  while (!done(data) && Clock::now() < deadline) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 5) <= 0) continue;
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n > 0) data.append(buf, static_cast<std::size_t>(n));
  }
  return data;
}

// Reads whatever arrives until nothing has come for `quiet`.
std::string read_quiet(int fd, milliseconds quiet = milliseconds(40)) {
  std::string data;
  const auto deadline = Clock::now() + milliseconds(2000);
  auto last = Clock::now();
  char buf[8192];
  while (Clock::now() - last < quiet && Clock::now() < deadline) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 5) <= 0) continue;
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n > 0) {
      data.append(buf, static_cast<std::size_t>(n));
      last = Clock::now();
    }
  }
  return data;
}

// Reads from the port until `want` bytes came or the time limit passes.
std::string port_read_until(BytePort& port, std::size_t want,
                            milliseconds limit = milliseconds(2000)) {
  std::string data;
  const auto deadline = Clock::now() + limit;
  std::uint8_t buf[4096];
  while (data.size() < want && Clock::now() < deadline) {
    const std::size_t n = port.read(buf);
    if (n > 0)
      data.append(reinterpret_cast<const char*>(buf), n);
    else
      std::this_thread::sleep_for(milliseconds(1));
  }
  return data;
}

int open_client(const std::string& path) {
  return ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Whether `port`'s output reaches a client that opens `path`: one short sentence, read back.
void expect_output_reaches(BytePort& port, const std::string& path) {
  const int c = open_client(path);
  ASSERT_GE(c, 0) << path;
  const std::string sentence = "$X*00\r\n";
  ASSERT_TRUE(port.write(sentence));
  EXPECT_EQ(read_until(c, [&](const std::string& d) { return d.size() >= sentence.size(); }),
            sentence);
  ::close(c);
}

// A fresh directory under /tmp, removed at the end of the test.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    std::string t = (std::filesystem::temp_directory_path() / "navemu-pty-XXXXXX").string();
    if (::mkdtemp(t.data()) == nullptr) throw std::runtime_error("mkdtemp");
    path = t;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

TEST(Pty, RawRoundTripKeepsCrAndDoesNotEcho) {
  auto port = open_pty({});
  const std::string slave = pty_slave_path(*port);
  ASSERT_EQ(slave.rfind("/dev/pts/", 0), 0u) << slave;
  EXPECT_EQ(port->describe(), "pty " + slave);
  const int c = open_client(slave);
  ASSERT_GE(c, 0);

  const std::string sentence = "$GPGGA,1,2,3*00\r\n";
  ASSERT_TRUE(port->write(sentence));
  const std::string got =
      read_until(c, [&](const std::string& d) { return d.size() >= sentence.size(); });
  EXPECT_EQ(got, sentence);  // CR stays CR (no ICRNL), nothing added (no OPOST)

  // Raw mode: our own output does not echo back as client input.
  std::this_thread::sleep_for(milliseconds(20));
  std::uint8_t buf[256];
  EXPECT_EQ(port->read(buf), 0u);

  // Commands written by the client come out of read() unchanged.
  const std::string cmd = "\xb5\x62\x06\x00\x00\x00\x06\x18\r\n";
  ASSERT_EQ(::write(c, cmd.data(), cmd.size()), static_cast<ssize_t>(cmd.size()));
  EXPECT_EQ(port_read_until(*port, cmd.size()), cmd);
  EXPECT_EQ(port->counters().bytes_read, cmd.size());
  EXPECT_EQ(port->counters().chunks_written, 1u);
  EXPECT_EQ(port->counters().errors, 0u);
  ::close(c);
}

TEST(Pty, SlaveIsWorldReadableAndWritable) {
  auto port = open_pty({});
  struct stat st {};
  ASSERT_EQ(::stat(pty_slave_path(*port).c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0666u);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
}

TEST(Pty, SymlinkIsCreatedAndRemovedWithItsLockFile) {
  TempDir dir;
  const std::string link = (dir.path / "gnss").string();
  auto port = open_pty({link});
  EXPECT_EQ(std::filesystem::read_symlink(link).string(), pty_slave_path(*port));
  EXPECT_EQ(port->describe(), "pty " + link + " -> " + pty_slave_path(*port));
  EXPECT_EQ(read_file(link + ".lock"), fmt::format("{}\n", ::getpid()));
  expect_output_reaches(*port, link);  // the link reaches the slave
  port.reset();
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(link)));
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(link + ".lock")));
}

// Another process owning a link: a child process that opens a port on `link`, reports its
// slave through a pipe and waits to be killed (SIGKILL: no destructor runs, as when navemu is
// killed).
class LinkOwner {
 public:
  explicit LinkOwner(const std::string& link) {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe2");
    const pid_t parent = ::getpid();
    pid_ = ::fork();
    if (pid_ < 0) throw std::runtime_error("fork");
    if (pid_ == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent) ::_exit(1);
      ::close(fds[0]);
      try {
        auto port = open_pty({link});
        const std::string slave = pty_slave_path(*port) + "\n";
        if (::write(fds[1], slave.data(), slave.size()) != static_cast<ssize_t>(slave.size()))
          ::_exit(1);
        for (;;) ::pause();
      } catch (...) {
        ::_exit(1);
      }
    }
    ::close(fds[1]);
    slave_ = read_until(fds[0], [](const std::string& d) { return d.find('\n') != d.npos; });
    ::close(fds[0]);
    if (!slave_.empty()) slave_.pop_back();
  }
  ~LinkOwner() { kill(); }
  LinkOwner(const LinkOwner&) = delete;
  LinkOwner& operator=(const LinkOwner&) = delete;
  pid_t pid() const { return pid_; }
  const std::string& slave() const { return slave_; }
  void kill() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }

 private:
  pid_t pid_ = -1;
  std::string slave_;
};

// The text of a process's /proc/PID/comm (its program name, at most 15 characters).
std::string program_name(pid_t pid) {
  std::string name = read_file(fmt::format("/proc/{}/comm", pid));
  if (!name.empty() && name.back() == '\n') name.pop_back();
  return name;
}

TEST(Pty, ALinkInUseIsRefusedAndAKilledOwnersLinkIsTakenOver) {
  TempDir dir;
  const std::string link = (dir.path / "gnss").string();
  LinkOwner owner(link);
  ASSERT_EQ(owner.slave().rfind("/dev/pts/", 0), 0u) << "the child could not open its port";
  ASSERT_EQ(std::filesystem::read_symlink(link).string(), owner.slave());

  // A second port on the link, in another process: refused, naming the owner; the owner's link
  // stays as it was.
  try {
    open_pty({link});
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), fmt::format("pty link {} is in use by {} (pid {})", link,
                                                 program_name(owner.pid()), owner.pid()));
  }
  EXPECT_EQ(std::filesystem::read_symlink(link).string(), owner.slave());
  EXPECT_EQ(read_file(link + ".lock"), fmt::format("{}\n", owner.pid()));

  // Within one process too: the lock belongs to the port, not to the process.
  auto mine = open_pty({(dir.path / "imu").string()});
  EXPECT_THROW(open_pty({(dir.path / "imu").string()}), std::runtime_error);
  mine.reset();

  // The owner is killed: its link and lock file stay behind, stale, and the next port takes
  // them over.
  owner.kill();
  ASSERT_TRUE(std::filesystem::is_symlink(link));
  auto next = open_pty({link});
  EXPECT_EQ(std::filesystem::read_symlink(link).string(), pty_slave_path(*next));
  EXPECT_EQ(read_file(link + ".lock"), fmt::format("{}\n", ::getpid()));
  expect_output_reaches(*next, link);
}

TEST(Pty, RefusesToReplaceARegularFileFollowALockSymlinkOrUseAMissingDirectory) {
  TempDir dir;
  const std::string file = (dir.path / "not-a-link").string();
  std::ofstream(file) << "keep me";
  try {
    open_pty({file});
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not a symlink"), std::string::npos) << e.what();
  }
  EXPECT_EQ(read_file(file), "keep me");
  EXPECT_FALSE(std::filesystem::exists(file + ".lock")) << "refused before taking the lock";

  // A lock file path that is a symlink is not followed (it could point anywhere).
  const std::string planted = (dir.path / "planted").string();
  std::filesystem::create_symlink(file, planted + ".lock");
  try {
    open_pty({planted});
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(planted + ".lock"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(planted)));
  EXPECT_EQ(read_file(file), "keep me");

  const std::string missing = (dir.path / "no-such-dir" / "gnss").string();
  try {
    open_pty({missing});
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
}

// A stand-in for gpsd's control socket (gpsd(8), "GPS DEVICE MANAGEMENT": one command line per
// connection here, answered "OK"): records each command and whether `link` existed when it came.
class FakeGpsdControl {
 public:
  FakeGpsdControl(const std::string& socket_path, const std::string& link) {
    fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", socket_path.c_str());
    if (fd_ < 0 || ::bind(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0 ||
        ::listen(fd_, 4) != 0)
      throw std::runtime_error("cannot listen on " + socket_path);
    thread_ = std::thread([this, link] {
      while (!stop_) {
        pollfd p{fd_, POLLIN, 0};
        if (::poll(&p, 1, 10) <= 0) continue;
        const int c = ::accept4(fd_, nullptr, nullptr, SOCK_CLOEXEC);
        if (c < 0) continue;
        std::string line =
            read_until(c, [](const std::string& d) { return d.find('\n') != d.npos; });
        line = line.substr(0, line.find('\n'));
        const bool link_there = std::filesystem::is_symlink(link);
        ::send(c, "OK\n", 3, MSG_NOSIGNAL);  // the port may have gone already: no SIGPIPE
        ::close(c);
        std::lock_guard<std::mutex> lock(mutex_);
        commands_.push_back(line + (link_there ? " (link there)" : " (no link)"));
      }
    });
  }
  ~FakeGpsdControl() {
    stop_ = true;
    thread_.join();
    ::close(fd_);
  }
  // The commands received, once `n` have come (at most 2 s).
  std::vector<std::string> commands(std::size_t n) {
    const auto deadline = Clock::now() + milliseconds(2000);
    for (;;) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (commands_.size() >= n || Clock::now() > deadline) return commands_;
      }
      std::this_thread::sleep_for(milliseconds(5));
    }
  }

 private:
  int fd_ = -1;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  std::mutex mutex_;
  std::vector<std::string> commands_;
};

TEST(Pty, GpsdIsToldWhenTheLinkComesAndGoes) {
  TempDir dir;
  const std::string link = (dir.path / "gnss").string();
  const std::string sock = (dir.path / "gpsd.sock").string();
  {
    FakeGpsdControl gpsd(sock, link);
    auto port = open_pty({link, 4096, sock});
    // Removed first (gpsd refuses to add a path it still has), then added, once the link is up.
    EXPECT_EQ(gpsd.commands(2), (std::vector<std::string>{"-" + link + " (link there)",
                                                          "+" + link + " (link there)"}));
    EXPECT_EQ(port->describe(), fmt::format("pty {} -> {}, announced to gpsd ({})", link,
                                            pty_slave_path(*port), sock));
    port.reset();
    // Removed again at close, before the link goes.
    EXPECT_EQ(gpsd.commands(3).back(), "-" + link + " (link there)");
    EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(link)));
  }
  // No gpsd listening: the port works all the same and says so.
  std::filesystem::remove(sock);
  auto port = open_pty({link, 4096, sock});
  EXPECT_EQ(port->describe(),
            fmt::format("pty {} -> {}, not announced to gpsd: gpsd control socket {}: No such "
                        "file or directory",
                        link, pty_slave_path(*port), sock));
  expect_output_reaches(*port, link);
}

TEST(Pty, ClientClosesAndReopensMidStream) {
  auto port = open_pty({});
  const std::string slave = pty_slave_path(*port);
  int c = open_client(slave);
  ASSERT_GE(c, 0);
  int seq = 0;
  for (; seq < 5; ++seq) ASSERT_TRUE(port->write(make_chunk(seq, 120)));
  std::string first = read_until(c, [](const std::string& d) { return d.size() >= 5 * 120; });
  std::vector<int> seqs;
  ASSERT_TRUE(parse_chunks(first, seqs));
  EXPECT_EQ(seqs, (std::vector<int>{0, 1, 2, 3, 4}));
  ::close(c);

  // Written while nobody has the slave open: kept (the port holds the slave) and delivered.
  for (; seq < 10; ++seq) ASSERT_TRUE(port->write(make_chunk(seq, 120)));
  c = open_client(slave);
  ASSERT_GE(c, 0);
  for (; seq < 15; ++seq) ASSERT_TRUE(port->write(make_chunk(seq, 120)));
  const std::string second =
      read_until(c, [](const std::string& d) { return d.size() >= 10 * 120; });
  seqs.clear();
  ASSERT_TRUE(parse_chunks(second, seqs));
  EXPECT_EQ(seqs, (std::vector<int>{5, 6, 7, 8, 9, 10, 11, 12, 13, 14}));
  port->service();
  EXPECT_EQ(port->counters().clients_connected, 2u);
  EXPECT_EQ(port->counters().chunks_dropped, 0u);
  EXPECT_EQ(port->counters().stale_flushes, 0u);
  ::close(c);
}

// Closing the master hangs the slave up, which flushes what a client has not read yet. The
// port's close waits (up to 0.5 s) for a client that has the slave open, so a run's last
// chunk reaches a slow reader; with no client, the close does not wait.
TEST(Pty, CloseLetsAClientReadTheLastChunk) {
  auto port = open_pty({});
  const int c = open_client(pty_slave_path(*port));
  ASSERT_GE(c, 0);
  const std::string last = "$GPRMC,last*00\r\n";
  ASSERT_TRUE(port->write(last));
  std::thread closer([&] { port.reset(); });
  std::this_thread::sleep_for(milliseconds(100));  // the client is slow to read
  const std::string got = read_until(c, [&](const std::string& d) { return d.size() >= last.size(); });
  closer.join();
  EXPECT_EQ(got, last);
  ::close(c);

  auto unread = open_pty({});
  ASSERT_TRUE(unread->write(last));
  const auto t0 = Clock::now();
  unread.reset();
  EXPECT_LT(Clock::now() - t0, milliseconds(400)) << "waited for a client that never opened the slave";
}

TEST(Pty, NobodyReadingNeverBlocksAndStaleOutputIsBounded) {
  const std::size_t max_backlog = 4096;
  auto port = open_pty({"", max_backlog});
  const auto t0 = Clock::now();
  int seq = 0;
  for (; seq < 1000; ++seq) port->write(make_chunk(seq, 600));
  const auto elapsed = Clock::now() - t0;
  // 1000 writes that never wait: milliseconds; a blocked write would hang the test instead.
  EXPECT_LT(elapsed, milliseconds(500));
  const PortCounters& k = port->counters();
  EXPECT_EQ(k.chunks_written + k.chunks_dropped, 1000u);
  // Stale output was discarded. Its byte count is only a lower bound (pty.cpp): while the
  // kernel's worker lags behind the writes, FIONREAD shows none of it, so count the flushes.
  EXPECT_GT(k.stale_flushes, 0u);
  EXPECT_GT(k.chunks_written, 900u);     // stale output made room for new chunks
  EXPECT_EQ(k.errors, 0u);

  // Between epochs: housekeeping. Then a client turns up and finds at most max_backlog bytes
  // of old output, all of it whole chunks.
  std::this_thread::sleep_for(milliseconds(10));
  port->service();
  const int c = open_client(pty_slave_path(*port));
  ASSERT_GE(c, 0);
  const std::string old = read_quiet(c);
  EXPECT_LE(old.size(), max_backlog);
  std::vector<int> seqs;
  EXPECT_TRUE(parse_chunks(old, seqs)) << old.size();
  for (int s : seqs) EXPECT_GE(s, 990);  // only the newest of the old chunks survived

  // New chunks arrive intact, in order, as the client reads them.
  for (int i = 0; i < 20; ++i, ++seq) {
    ASSERT_TRUE(port->write(make_chunk(seq, 600)));
    const std::string got = read_until(c, [](const std::string& d) { return d.size() >= 600; });
    ASSERT_EQ(got, make_chunk(seq, 600)) << "chunk " << seq;
  }
  ::close(c);
}

TEST(Pty, ChunkBiggerThanThePtyIsCompletedFromTheTail) {
  auto port = open_pty({"", 1 << 20});
  const int c = open_client(pty_slave_path(*port));
  ASSERT_GE(c, 0);
  const std::string big = make_chunk(1, 40000);  // more than the ~17 KB a pty holds
  const std::string small = make_chunk(2, 100);
  std::atomic<std::size_t> progress{0};
  std::string received;
  std::thread reader([&] {
    received = read_until(
        c,
        [&](const std::string& d) {
          progress = d.size();
          return d.size() >= big.size() + small.size();
        },
        milliseconds(3000));
  });
  EXPECT_TRUE(port->write(big));  // (no ASSERT while the reader thread runs)
  const auto deadline = Clock::now() + milliseconds(2000);
  while (port->counters().bytes_written < big.size() && Clock::now() < deadline) {
    std::this_thread::sleep_for(milliseconds(1));
    port->service();  // sends the tail as the reader makes room
  }
  EXPECT_EQ(port->counters().bytes_written, big.size());
  // Once the big one has been read, the next chunk follows it.
  while (progress < big.size() && Clock::now() < deadline)
    std::this_thread::sleep_for(milliseconds(1));
  EXPECT_TRUE(port->write(small));
  reader.join();
  EXPECT_TRUE(received == big + small) << "received " << received.size() << " bytes";
  EXPECT_EQ(port->counters().chunks_written, 2u);
  EXPECT_EQ(port->counters().stale_flushes, 0u);
  ::close(c);
}

TEST(Pty, TailThatCannotDrainGoesStaleWithItsChunk) {
  auto port = open_pty({"", 4096});
  const std::string big = make_chunk(1, 40000);
  ASSERT_TRUE(port->write(big));  // partly taken, tail kept
  const std::uint64_t taken = port->counters().bytes_written;
  EXPECT_LT(taken, big.size());
  // Nobody reads: the next chunk finds the tail stuck; the whole backlog is discarded (the
  // head of the big chunk included) and the new chunk goes out on its own.
  ASSERT_TRUE(port->write(make_chunk(2, 100)));
  EXPECT_GE(port->counters().stale_bytes_flushed, big.size() - taken);  // the tail, at least
  EXPECT_EQ(port->counters().chunks_written, 2u);
  const int c = open_client(pty_slave_path(*port));
  ASSERT_GE(c, 0);
  EXPECT_EQ(read_quiet(c), make_chunk(2, 100));
  ::close(c);
}

TEST(Pty, SlavePathIsEmptyForOtherPorts) {
  auto udp_port = open_udp_sender({"127.0.0.1", 9});
  EXPECT_EQ(pty_slave_path(*udp_port), "");
}

}  // namespace
}  // namespace navemu::transport
