// Pseudo-terminal port: pty(7), posix_openpt(3), termios(3), tty_ioctl(4), inotify(7).
//
// What the kernel does (Linux 6.x, verified by experiment and by the tests of this module):
// - Bytes written on the master land in the slave's input queue: first the n_tty line
//   discipline's read buffer, N_TTY_BUF_SIZE - 1 = 4095 bytes in raw mode, then the port's
//   flip buffers. With nobody reading, the master accepts about 17 KB in all, then write()
//   accepts part of a chunk and then fails with EAGAIN.
// - ioctl(slave, FIONREAD) (the same request as TIOCINQ) reports only the n_tty read buffer,
//   so it saturates at 4095 however much more waits behind it. TIOCOUTQ on the master reports
//   0 (a pty has no output queue of its own), so it cannot measure the backlog either.
// - tcflush(slave, TCIFLUSH) empties both the n_tty buffer and the flip buffers (tty_ioctl
//   flushes the port's tty_buffer before the line discipline's own flush): afterwards the
//   master again takes the full 17 KB, and a client that opens the slave reads only what was
//   written after the flush.
// - The move from the flip buffers into n_tty runs in a kernel worker (flush_to_ldisc), not
//   in the writer's write(2): right after a write FIONREAD may not include it yet. In a tight
//   loop of 1000 writes the queue was seen to grow past 12 KB while FIONREAD lagged behind.
// Hence the stale rule: a read buffer that is full counts as stale whatever the limit, and
// bytes written within the last few milliseconds are counted as unread on top of FIONREAD
// (an upper bound, so a burst of chunks cannot slip past the limit while the worker lags).

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/inotify.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "transports/byte_port.hpp"
#include "transports/file_lock.hpp"
#include "transports/gpsd_control.hpp"

namespace navemu::transport {
namespace {

// The n_tty read buffer in raw mode (N_TTY_BUF_SIZE - 1): the most FIONREAD can report.
constexpr std::size_t kLdiscCapacity = 4095;
// The pending-tail buffer is reserved once with this capacity; only a chunk bigger than the
// whole pty (about 17 KB) can make it grow.
constexpr std::size_t kTailReserve = 32 * 1024;
// How long the kernel worker may take to move written bytes into n_tty (see above); it
// usually takes microseconds, and milliseconds on a busy machine.
constexpr std::chrono::milliseconds kPushLag{5};
// How long gpsd may take to answer a removal on its control socket (it answers at once).
constexpr std::chrono::milliseconds kGpsdTimeout{2000};
// At close, how long a client that has the slave open gets to read what it has not read yet.
constexpr std::chrono::milliseconds kDrainTimeout{500};

// Bytes written within the last kPushLag (at least): two consecutive buckets, each at least
// kPushLag long, the current one younger than kPushLag, so together they cover the window.
class RecentBytes {
 public:
  using Clock = std::chrono::steady_clock;
  void add(std::size_t n, Clock::time_point now) {
    advance(now);
    current_ += n;
  }
  std::size_t total(Clock::time_point now) {
    advance(now);
    return current_ + previous_;
  }
  void clear() { current_ = previous_ = 0; }

 private:
  void advance(Clock::time_point now) {
    const auto age = now - start_;
    if (age < kPushLag) return;
    previous_ = age < 2 * kPushLag ? current_ : 0;
    current_ = 0;
    start_ = now;
  }
  Clock::time_point start_{};
  std::size_t current_ = 0;
  std::size_t previous_ = 0;
};

std::string errno_text(int e) { return std::error_code(e, std::generic_category()).message(); }

// Refuses a link path that exists and is not a symlink, and one whose directory does not exist.
void check_link_path(const std::string& link) {
  struct stat st {};
  if (::lstat(link.c_str(), &st) == 0) {
    if (!S_ISLNK(st.st_mode))
      throw std::runtime_error(
          fmt::format("pty link {}: exists and is not a symlink; refusing to replace it", link));
  } else if (errno != ENOENT) {
    throw std::runtime_error(fmt::format("pty link {}: {}", link, errno_text(errno)));
  }
  const std::filesystem::path dir = std::filesystem::path(link).parent_path();
  std::error_code ec;
  if (!dir.empty() && !std::filesystem::is_directory(dir, ec))
    throw std::runtime_error(
        fmt::format("pty link {}: directory {} does not exist", link, dir.string()));
}

// Creates (or atomically replaces) the symlink `link` -> `target` (check_link_path() first).
void make_link(const std::string& link, const std::string& target) {
  // symlink(2) to a temporary name, then rename(2) over the link: clients never see the path
  // missing while an old link is replaced.
  const std::string tmp = fmt::format("{}.navemu-{}", link, ::getpid());
  ::unlink(tmp.c_str());
  if (::symlink(target.c_str(), tmp.c_str()) != 0)
    throw std::runtime_error(fmt::format("pty link {}: {}", link, errno_text(errno)));
  if (::rename(tmp.c_str(), link.c_str()) != 0) {
    const int e = errno;
    ::unlink(tmp.c_str());
    throw std::runtime_error(fmt::format("pty link {}: {}", link, errno_text(e)));
  }
}

// The lock that makes one port the owner of a link: LINK.lock beside it, a regular file with
// the owner's pid in it, held with flock(2) for the port's lifetime. The kernel drops the lock
// when its owner dies however it dies, so the link and lock file a killed instance leaves
// behind are taken over; a live owner's are refused.
class LinkLock {
 public:
  explicit LinkLock(const std::string& link) : path_(link + ".lock") {
    // A previous owner removes the file at exit, possibly between our open(2) and our flock(2):
    // then the lock we got is on a file nobody else will find, and we start again. Twice in a
    // row takes three instances racing; five rounds are plenty.
    for (int round = 0; round < 5; ++round) {
      Fd f(::open(path_.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644));
      if (f.fd < 0)
        throw std::runtime_error(
            fmt::format("pty link {}: lock file {}: {}", link, path_, errno_text(errno)));
      struct stat held {}, named {};
      if (::fstat(f.fd, &held) != 0 || !S_ISREG(held.st_mode))
        throw std::runtime_error(
            fmt::format("pty link {}: lock file {} is not a regular file", link, path_));
      if (!try_lock_exclusive(f.fd, fmt::format("pty link {}: lock file {}", link, path_)))
        throw std::runtime_error(
            fmt::format("pty link {} is in use by {}", link, lock_holder(f.fd)));
      if (::stat(path_.c_str(), &named) != 0 || named.st_dev != held.st_dev ||
          named.st_ino != held.st_ino)
        continue;
      // The pid is for people (cat LINK.lock); the lock itself is what counts.
      const std::string pid = fmt::format("{}\n", ::getpid());
      [[maybe_unused]] const bool written =
          ::ftruncate(f.fd, 0) == 0 && ::pwrite(f.fd, pid.data(), pid.size(), 0) > 0;
      std::swap(fd_.fd, f.fd);
      return;
    }
    throw std::runtime_error(
        fmt::format("pty link {}: lock file {} keeps being replaced", link, path_));
  }
  LinkLock(const LinkLock&) = delete;
  LinkLock& operator=(const LinkLock&) = delete;
  // Removes the lock file while still holding the lock (Fd closes it afterwards).
  ~LinkLock() {
    if (fd_.fd >= 0) ::unlink(path_.c_str());
  }

 private:
  std::string path_;
  Fd fd_;
};

class PtyPort final : public BytePort {
 public:
  explicit PtyPort(const PtyOptions& opt)
      : gpsd_socket_(opt.gpsd_socket), max_backlog_(opt.max_backlog_bytes) {
    // The link is ours before anything else happens: a path that cannot be a link is refused
    // first, then one that another port owns.
    if (!opt.link_path.empty()) {
      check_link_path(opt.link_path);
      link_lock_.emplace(opt.link_path);
    }
    // Master: non-blocking, close-on-exec, never our controlling terminal.
    master_.fd = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC | O_NONBLOCK);
    if (master_.fd < 0)
      throw std::runtime_error(fmt::format("pty: posix_openpt: {}", errno_text(errno)));
    ::fcntl(master_.fd, F_SETFD, FD_CLOEXEC);
    ::fcntl(master_.fd, F_SETFL, ::fcntl(master_.fd, F_GETFL) | O_NONBLOCK);
    if (::grantpt(master_.fd) != 0 || ::unlockpt(master_.fd) != 0)
      throw std::runtime_error(fmt::format("pty: unlockpt: {}", errno_text(errno)));
    std::array<char, 128> name{};
    if (::ptsname_r(master_.fd, name.data(), name.size()) != 0)
      throw std::runtime_error(fmt::format("pty: ptsname: {}", errno_text(errno)));
    slave_path_ = name.data();

    // The slave stays open in this process: the tty (and its settings) lives on while clients
    // close and reopen it, and the master never reads EIO for want of a slave.
    slave_.fd = ::open(slave_path_.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC | O_NONBLOCK);
    if (slave_.fd < 0)
      throw std::runtime_error(fmt::format("pty {}: {}", slave_path_, errno_text(errno)));
    // Raw mode: no echo of our output back into the master, no CR -> LF translation.
    termios tio{};
    if (::tcgetattr(slave_.fd, &tio) != 0)
      throw std::runtime_error(
          fmt::format("pty {}: tcgetattr: {}", slave_path_, errno_text(errno)));
    ::cfmakeraw(&tio);
    if (::tcsetattr(slave_.fd, TCSANOW, &tio) != 0)
      throw std::runtime_error(
          fmt::format("pty {}: tcsetattr: {}", slave_path_, errno_text(errno)));
    // gpsd opens the device as root and then drops privileges: the slave must stay usable.
    if (::fchmod(slave_.fd, 0666) != 0)
      throw std::runtime_error(
          fmt::format("pty {}: chmod 0666: {}", slave_path_, errno_text(errno)));

    // Opens by clients are counted from inotify IN_OPEN events on the slave; without inotify
    // the port works the same, it only cannot count them. Closes are watched too because
    // inotify merges identical consecutive events: open, open would read as one open, while
    // open, close, open stays three events. (Two clients opening with no close in between
    // still count as one.)
    inotify_.fd = ::inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    if (inotify_.fd >= 0 &&
        ::inotify_add_watch(inotify_.fd, slave_path_.c_str(), IN_OPEN | IN_CLOSE) < 0) {
      ::close(inotify_.fd);
      inotify_.fd = -1;
    }

    tail_.reserve(kTailReserve);
    if (!opt.link_path.empty()) {
      make_link(opt.link_path, slave_path_);
      link_path_ = opt.link_path;
    }
    if (!gpsd_socket_.empty()) gpsd_status_ = announce_to_gpsd();
  }

  ~PtyPort() override {
    // The clients read what is left first; then gpsd is told (it closes its end of the pty),
    // the link goes, then (members) the pty and, last, the lock.
    drain();
    if (!gpsd_socket_.empty()) {
      try {
        gpsd_control(gpsd_socket_, "-" + client_path(), kGpsdTimeout);
      } catch (const std::runtime_error&) {
        // gpsd has gone: nothing to withdraw from.
      }
    }
    // Remove the symlink only while it still names our slave (the lock keeps other navemu
    // instances off it, but anything else may have replaced it).
    if (!link_path_.empty()) {
      std::array<char, 256> target{};
      const ssize_t n = ::readlink(link_path_.c_str(), target.data(), target.size() - 1);
      if (n > 0 && std::string_view(target.data(), static_cast<std::size_t>(n)) == slave_path_)
        ::unlink(link_path_.c_str());
    }
  }

  PtyPort(const PtyPort&) = delete;
  PtyPort& operator=(const PtyPort&) = delete;

  using BytePort::write;

  bool write(std::span<const std::uint8_t> chunk) override {
    if (chunk.empty()) return true;
    if (tail_pending()) {
      // The end of the previous chunk is still waiting: a client that has not made room for
      // it since then has stopped reading, and all it has not read is stale.
      if (!flush_tail()) discard_stale(unread_bytes());
    } else {
      // Unread output that, with this chunk, would exceed the limit is discarded rather than
      // delivered late; a full n_tty buffer may hide any amount behind it, so it is stale too.
      const std::size_t queued = unread_bytes();
      const std::size_t estimate = queued + recent_.total(RecentBytes::Clock::now());
      if (queued >= kLdiscCapacity || (estimate > 0 && estimate + chunk.size() > max_backlog_))
        discard_stale(queued);
    }
    if (tail_pending()) return drop(chunk.size());  // only when tcflush failed

    const ssize_t n = write_master(chunk.data(), chunk.size());
    if (n <= 0) return drop(chunk.size());
    const auto sent = static_cast<std::size_t>(n);
    counters_.chunks_written++;
    counters_.bytes_written += sent;
    // The kernel took part of the chunk: the rest goes first next time, so the client never
    // sees a torn chunk (assign() stays within the capacity reserved at open).
    if (sent < chunk.size()) {
      tail_.assign(chunk.begin() + static_cast<std::ptrdiff_t>(sent), chunk.end());
      tail_off_ = 0;
    }
    return true;
  }

  std::size_t read(std::span<std::uint8_t> buf) override {
    if (buf.empty()) return 0;
    const ssize_t n = ::read(master_.fd, buf.data(), buf.size());
    if (n > 0) {
      counters_.bytes_read += static_cast<std::uint64_t>(n);
      return static_cast<std::size_t>(n);
    }
    // EIO would mean no slave is open, which cannot happen while we hold one.
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) counters_.errors++;
    return 0;
  }

  // Sends the rest of a partly written chunk as the client makes room. No stale check here:
  // the queue holds only the latest chunk, which a client may be reading right now.
  void service() override {
    count_opens();
    flush_tail();
  }

  std::string describe() const override {
    return (link_path_.empty() ? "pty " + slave_path_
                               : "pty " + link_path_ + " -> " + slave_path_) +
           gpsd_status_;
  }

  const std::string& slave_path() const { return slave_path_; }

 private:
  bool tail_pending() const { return tail_off_ < tail_.size(); }

  // The path clients open: the link, or the slave when there is none.
  const std::string& client_path() const { return link_path_.empty() ? slave_path_ : link_path_; }

  // Puts the port into gpsd's device pool, as a hotplug script does for a new USB receiver
  // (gpsd(8), "GPS DEVICE MANAGEMENT"). gpsd keeps a device it has read from in its pool after
  // the pty hung up (a previous navemu exited, or was killed before it could remove the device)
  // and never reopens it, and answers ERROR to "+" for a path already in the pool (gpsd 3.22,
  // by experiment); so "-" first (ERROR when gpsd does not have it), then "+", whose answer
  // gpsd gives only after probing the device with the data this port has yet to send, so it is
  // not awaited. Returns the part of describe() that tells the outcome; a gpsd that cannot be
  // reached is not an error.
  std::string announce_to_gpsd() {
    const std::string path = client_path();
    try {
      gpsd_control(gpsd_socket_, "-" + path, kGpsdTimeout);
      gpsd_control(gpsd_socket_, "+" + path, std::chrono::milliseconds(0));
      return fmt::format(", announced to gpsd ({})", gpsd_socket_);
    } catch (const std::runtime_error& e) {
      return fmt::format(", not announced to gpsd: {}", e.what());
    }
  }

  // One non-blocking write(2) on the master; -1 with errno on failure (EAGAIN not counted).
  ssize_t write_master(const std::uint8_t* data, std::size_t size) {
    ssize_t n;
    do n = ::write(master_.fd, data, size);
    while (n < 0 && errno == EINTR);
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) counters_.errors++;
    if (n > 0) recent_.add(static_cast<std::size_t>(n), RecentBytes::Clock::now());
    return n;
  }

  // Sends what is left of a partly written chunk; true when nothing is left.
  bool flush_tail() {
    if (!tail_pending()) return true;
    const ssize_t n = write_master(tail_.data() + tail_off_, tail_.size() - tail_off_);
    if (n > 0) {
      tail_off_ += static_cast<std::size_t>(n);
      counters_.bytes_written += static_cast<std::uint64_t>(n);
    } else if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) {
      counters_.bytes_dropped += tail_.size() - tail_off_;  // hard error: give the tail up
      tail_off_ = tail_.size();
    }
    if (tail_pending()) return false;
    tail_.clear();
    tail_off_ = 0;
    return true;
  }

  // Bytes waiting unread on the slave side (FIONREAD, alias TIOCINQ; at most kLdiscCapacity).
  std::size_t unread_bytes() {
    int n = 0;
    if (::ioctl(slave_.fd, FIONREAD, &n) != 0) {
      counters_.errors++;
      return 0;
    }
    return n > 0 ? static_cast<std::size_t>(n) : 0;
  }

  // Throws away everything the client has not read (and a pending tail, whose head goes with
  // it). Bytes beyond the n_tty buffer are discarded too but cannot be counted, so
  // stale_bytes_flushed is a lower bound.
  void discard_stale(std::size_t queued) {
    if (::tcflush(slave_.fd, TCIFLUSH) != 0) {
      counters_.errors++;
      return;
    }
    recent_.clear();
    counters_.stale_flushes++;
    counters_.stale_bytes_flushed += queued + (tail_.size() - tail_off_);
    tail_.clear();
    tail_off_ = 0;
  }

  bool drop(std::size_t size) {
    counters_.chunks_dropped++;
    counters_.bytes_dropped += size;
    return false;
  }

  // Closing the master hangs the slave up, which flushes its input queue (tty_vhangup): a
  // client still reading would lose the last bytes written, e.g. a run's last epoch. So while a
  // client has the slave open, wait (at most kDrainTimeout) until it has read everything,
  // including bytes the kernel may not show in FIONREAD yet (written within kPushLag).
  void drain() {
    const auto until = RecentBytes::Clock::now() + kDrainTimeout;
    do {
      count_opens();
      flush_tail();
      if (clients_open_ == 0 ||
          (!tail_pending() && unread_bytes() == 0 && recent_.total(RecentBytes::Clock::now()) == 0))
        return;
      ::usleep(2000);
    } while (RecentBytes::Clock::now() < until);
  }

  // Drains inotify(7) events: every IN_OPEN is a client opening the slave, every IN_CLOSE one
  // closing it.
  void count_opens() {
    if (inotify_.fd < 0) return;
    alignas(inotify_event) std::array<char, 1024> buf;
    for (int round = 0; round < 16; ++round) {
      const ssize_t n = ::read(inotify_.fd, buf.data(), buf.size());
      if (n <= 0) return;
      for (std::size_t off = 0; off + sizeof(inotify_event) <= static_cast<std::size_t>(n);) {
        inotify_event ev{};
        std::memcpy(&ev, buf.data() + off, sizeof ev);
        if ((ev.mask & IN_OPEN) != 0) {
          counters_.clients_connected++;
          clients_open_++;
        }
        if ((ev.mask & IN_CLOSE) != 0 && clients_open_ > 0) clients_open_--;
        off += sizeof(inotify_event) + ev.len;
      }
    }
  }

  std::optional<LinkLock> link_lock_;  // first: released last, after the link is gone
  Fd master_;
  Fd slave_;
  Fd inotify_;
  std::string slave_path_;
  std::string link_path_;
  std::string gpsd_socket_;  // gpsd's control socket; empty: gpsd is not told
  std::string gpsd_status_;  // ", announced to gpsd (...)" for describe()
  std::size_t max_backlog_;
  RecentBytes recent_;              // written lately, possibly not yet visible to FIONREAD
  std::vector<std::uint8_t> tail_;  // unsent end of the last chunk, reserved once
  std::size_t tail_off_ = 0;
  std::uint64_t clients_open_ = 0;  // opens of the slave not yet closed (inotify)
};

}  // namespace

std::unique_ptr<BytePort> open_pty(const PtyOptions& opt) { return std::make_unique<PtyPort>(opt); }

std::string pty_slave_path(const BytePort& port) {
  const auto* pty = dynamic_cast<const PtyPort*>(&port);
  return pty != nullptr ? pty->slave_path() : std::string{};
}

}  // namespace navemu::transport
