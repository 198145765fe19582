#pragma once
// Helpers for the tests of `navemu run` in real time against real clients (gpsd) and of its
// behaviour on a pty: child processes that never outlive a test, temporary folders, free
// ports, a pty reader that time-stamps every sentence, a gpsd JSON client, and parsers of
// navemu's start-up, status and summary lines on stderr.
//
// Every wait has a deadline. Children run in their own process group, get SIGKILL if the test
// process dies (PR_SET_PDEATHSIG), and are stopped (SIGTERM, then SIGKILL) and reaped by the
// destructor of their Child, so a failing ASSERT leaves no process behind.

#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "models/geodesy.hpp"
#include "core/time.hpp"
#include "protocols/nmea.hpp"
#include "protocols/truth_datagram.hpp"
#include "tests/test_support.hpp"

namespace navemu::test::clients {

namespace fs = std::filesystem;

// --- Clocks.

inline double clock_s(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
inline double mono_s() { return clock_s(CLOCK_MONOTONIC); }
inline double real_s() { return clock_s(CLOCK_REALTIME); }

inline void sleep_s(double s) {
  if (s > 0) std::this_thread::sleep_for(std::chrono::duration<double>(s));
}

// Calls `done` every `poll_s` until it returns true (true) or `timeout_s` has passed (false).
template <class F>
bool wait_until(F done, double timeout_s, double poll_s = 0.02) {
  const double end = mono_s() + timeout_s;
  for (;;) {
    if (done()) return true;
    if (mono_s() >= end) return false;
    sleep_s(poll_s);
  }
}

// The GPS time an `events:` entry starts at, from navemu's line at start "navemu: event: <what>,
// from <ISO> (WEEK:TOW.mmm) ..." (to the millisecond); nullopt when not printed.
inline std::optional<GpsTime> announced_event_start(const std::string& log, const std::string& what) {
  const std::regex re("navemu: event: " + what + "[^\n]*\\((\\d+):(\\d+)\\.(\\d{3})\\)");
  std::smatch m;
  if (!std::regex_search(log, m, re)) return std::nullopt;
  return GpsTime{(std::stoll(m[1]) * 604800 + std::stoll(m[2])) * 1'000'000'000 + std::stoll(m[3]) * 1'000'000};
}

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline std::string tail(const std::string& s, std::size_t n = 3000) {
  return s.size() <= n ? s : "..." + s.substr(s.size() - n);
}

// --- Folders, programs, ports.

// A fresh folder /tmp/navemu-clients-NAME-XXXXXX, removed at the end unless
// NAVEMU_KEEP_TEST_DIRS is set. Mode 0755: gpsd drops privileges after opening its device
// (TESTING.md) and must still be able to reach the pty link and reopen it.
class TempDir {
 public:
  explicit TempDir(const std::string& name) {
    std::string templ = (fs::temp_directory_path() / ("navemu-clients-" + name + "-XXXXXX")).string();
    if (::mkdtemp(templ.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = templ;
    ::chmod(path_.c_str(), 0755);
  }
  ~TempDir() {
    if (std::getenv("NAVEMU_KEEP_TEST_DIRS") == nullptr) {
      std::error_code ec;
      fs::remove_all(path_, ec);
    }
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }
  fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

// A port that was free a moment ago on 127.0.0.1 (SOCK_STREAM or SOCK_DGRAM): bind port 0 and
// ask the kernel which one it gave. Tests run in parallel, so never a fixed port.
inline int free_port(int type) {
  const int fd = ::socket(AF_INET, type | SOCK_CLOEXEC, 0);
  if (fd < 0) return -1;
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  int port = -1;
  socklen_t len = sizeof a;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) == 0)
    port = ntohs(a.sin_port);
  ::close(fd);
  return port;
}

// --- Child processes.

class Child {
 public:
  Child() = default;
  // Starts argv[0] (a path) with standard input from /dev/null and standard output and error
  // appended to the given files.
  Child(const std::vector<std::string>& argv, const fs::path& out, const fs::path& err) {
    start(argv, out, err);
  }
  ~Child() { stop(); }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  bool start(const std::vector<std::string>& argv, const fs::path& out, const fs::path& err) {
    // Everything the child needs is prepared before fork(): after it, only async-signal-safe
    // calls (the test process may have other threads).
    std::vector<std::string> args = argv;
    std::vector<char*> cargv;
    for (std::string& a : args) cargv.push_back(a.data());
    cargv.push_back(nullptr);
    const std::string out_s = out.string(), err_s = err.string();
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid < 0) return false;
    if (pid == 0) {
      ::setpgid(0, 0);
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent) ::_exit(126);  // the parent died before prctl
      struct sigaction sa {};
      sa.sa_handler = SIG_DFL;
      ::sigaction(SIGPIPE, &sa, nullptr);
      sigset_t none;
      ::sigemptyset(&none);
      ::sigprocmask(SIG_SETMASK, &none, nullptr);
      const int in_fd = ::open("/dev/null", O_RDONLY);
      const int out_fd = ::open(out_s.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
      const int err_fd = ::open(err_s.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
      if (in_fd < 0 || out_fd < 0 || err_fd < 0) ::_exit(125);
      ::dup2(in_fd, 0);
      ::dup2(out_fd, 1);
      ::dup2(err_fd, 2);
      ::execv(cargv[0], cargv.data());
      static const char msg[] = "exec failed\n";
      [[maybe_unused]] const ssize_t w = ::write(2, msg, sizeof msg - 1);
      ::_exit(127);
    }
    ::setpgid(pid, pid);  // also here, so that signals to the group work at once
    pid_ = pid;
    status_.reset();
    return true;
  }

  pid_t pid() const { return pid_; }

  bool running() {
    reap(false);
    return pid_ > 0 && !status_;
  }

  // The wait(2) status once the child has exited within `timeout_s`; none if still running.
  std::optional<int> wait_exit(double timeout_s) {
    wait_until([&] { return !running(); }, timeout_s, 0.005);
    return status_;
  }

  // Sends a signal to the child only.
  void signal(int sig) {
    if (running()) ::kill(pid_, sig);
  }

  // SIGTERM to the child's process group, up to `grace_s` for it to exit, then SIGKILL; reaps
  // it. Returns its wait status.
  std::optional<int> stop(double grace_s = 3.0) {
    if (pid_ <= 0) return status_;
    if (running()) {
      ::kill(-pid_, SIGTERM);
      if (!wait_exit(grace_s)) {
        ::kill(-pid_, SIGKILL);
        reap(true);
      }
    }
    return status_;
  }

 private:
  void reap(bool block) {
    if (pid_ <= 0 || status_) return;
    int st = 0;
    const pid_t r = ::waitpid(pid_, &st, block ? 0 : WNOHANG);
    if (r == pid_) status_ = st;
  }

  pid_t pid_ = -1;
  std::optional<int> status_;
};

inline std::string describe_status(std::optional<int> st) {
  if (!st) return "still running";
  if (WIFEXITED(*st)) return "exit code " + std::to_string(WEXITSTATUS(*st));
  if (WIFSIGNALED(*st)) return "killed by signal " + std::to_string(WTERMSIG(*st));
  return "status " + std::to_string(*st);
}

// Resident memory of a process, kB (VmRSS of /proc/PID/status); 0 when unknown.
inline long rss_kb(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return 0;
}

// --- navemu run.

// One status line: "navemu: 12:48:13 UTC gnss 80 ep (3D 10/11 sv PDOP ...) imu 0 smp | jitter
// ... | late 0 skipped 0 dropped 0 chunks 0 frames | truth ok (accepted 501, rejected 0)".
struct StatusLine {
  int second_of_day = 0;
  long epochs = 0;
  std::string fix;  // "3D 10/11 sv PDOP 1.4 ...", "no fix 0/0 sv"
  long late = 0, skipped = 0, dropped = 0;  // dropped: output chunks + CAN frames
  std::string truth;  // ok, extrapolating, rejecting, lost (real time); ok, rejecting, paused
  bool truth_ok = false;  // the sensors have truth: ok or extrapolating
  std::string truth_counts;  // "accepted 501, rejected 0", or empty
};

inline std::vector<StatusLine> status_lines(const std::string& err) {
  static const std::regex re(
      R"(^navemu: (\d\d):(\d\d):(\d\d) UTC gnss (\d+) ep \((.*)\) imu .*\| late (\d+) skipped (\d+) dropped (\d+) chunks (\d+) frames.* \| truth (ok|extrapolating|rejecting|lost|paused)[^(]*(?:\((.*)\))?$)");
  std::vector<StatusLine> out;
  std::stringstream ss(err);
  for (std::string line; std::getline(ss, line);) {
    std::smatch m;
    if (!std::regex_search(line, m, re)) continue;
    StatusLine s;
    s.second_of_day = std::stoi(m[1]) * 3600 + std::stoi(m[2]) * 60 + std::stoi(m[3]);
    s.epochs = std::stol(m[4]);
    s.fix = m[5];
    s.late = std::stol(m[6]);
    s.skipped = std::stol(m[7]);
    s.dropped = std::stol(m[8]) + std::stol(m[9]);
    s.truth = m[10];
    s.truth_ok = s.truth == "ok" || s.truth == "extrapolating";
    s.truth_counts = m[11];
    out.push_back(s);
  }
  return out;
}

// The line `navemu run` prints at exit.
struct RunSummary {
  double wall_s = 0;
  long epochs = 0, fixes = 0, late = 0, skipped = 0, chunks_dropped = 0;
  long truth_accepted = 0, truth_rejected = 0, truth_lost = 0;
  long stale_bytes_flushed = 0, stale_flushes = 0, client_bytes = 0;  // summed over the GNSS ports
  std::string truth_reasons;  // "crc 1, backwards 2; resync 1", or empty
};

inline std::optional<RunSummary> run_summary(const std::string& err) {
  static const std::regex re(
      R"(navemu run: stopped after ([0-9.]+) s: (\d+) GNSS epochs \((\d+) with a fix, (\d+) late, (\d+) skipped\).* (\d+) output chunks dropped, (\d+) stale bytes flushed in (\d+) flushes, (\d+) bytes from clients, .*truth (\d+) accepted / (\d+) rejected / (\d+) lost unread(?: \((.*)\))?)");
  std::smatch m;
  if (!std::regex_search(err, m, re)) return std::nullopt;
  RunSummary s;
  s.wall_s = std::stod(m[1]);
  s.epochs = std::stol(m[2]);
  s.fixes = std::stol(m[3]);
  s.late = std::stol(m[4]);
  s.skipped = std::stol(m[5]);
  s.chunks_dropped = std::stol(m[6]);
  s.stale_bytes_flushed = std::stol(m[7]);
  s.stale_flushes = std::stol(m[8]);
  s.client_bytes = std::stol(m[9]);
  s.truth_accepted = std::stol(m[10]);
  s.truth_rejected = std::stol(m[11]);
  s.truth_lost = std::stol(m[12]);
  s.truth_reasons = m[13];
  return s;
}

// `navemu run CONFIG --duration S` on a configuration written into the test's folder; its
// standard error (start-up lines, status lines, summary) goes to NAME.stderr there. The
// duration is only a safety net: tests stop it themselves. `prefix` runs navemu through another
// program (e.g. setpriv to drop root).
class NavemuRun {
 public:
  NavemuRun(const TempDir& dir, const std::string& name, const std::string& config_yaml,
            double duration_s, const std::vector<std::string>& extra = {},
            const std::vector<std::string>& prefix = {})
      : err_(dir / (name + ".stderr")) {
    const fs::path cfg = dir / (name + ".yaml");
    std::ofstream(cfg) << config_yaml;
    std::vector<std::string> argv = prefix;
    for (const std::string& a : {navemu_binary().string(), std::string("run"), cfg.string(),
                                 std::string("--duration"), std::to_string(duration_s)})
      argv.push_back(a);
    argv.insert(argv.end(), extra.begin(), extra.end());
    started_mono_ = mono_s();
    child_.start(argv, dir / (name + ".stdout"), err_);
  }

  Child& child() { return child_; }
  double started_mono() const { return started_mono_; }
  std::string err() const { return slurp(err_); }
  std::string diagnostics() const {
    return "\n--- navemu stderr (" + err_.string() + ") ---\n" + tail(err()) + "\n---";
  }

  // Waits until the pty link exists and navemu has announced it ("GNSS NMEA on pty ..." or,
  // for a u-blox profile, "GNSS UBX/NMEA on pty ..."); false at once if navemu has exited.
  bool wait_for_pty(const fs::path& link, double timeout_s) {
    return wait_until(
               [&] {
                 const std::string e = err();
                 return (fs::exists(link) && (e.find("GNSS NMEA on pty") != std::string::npos ||
                                              e.find("GNSS UBX/NMEA on pty") != std::string::npos)) ||
                        !child_.running();
               },
               timeout_s) &&
           child_.running();
  }

  // The UDP port of the truth source (configured as port 0: the kernel picks a free one, and
  // the start-up line "navemu: truth: truth datagrams on udp port N" says which).
  std::optional<int> wait_for_udp_port(double timeout_s) {
    static const std::regex re(R"(truth datagrams on udp port (\d+))");
    std::optional<int> port;
    wait_until(
        [&] {
          const std::string e = err();
          std::smatch m;
          if (std::regex_search(e, m, re)) port = std::stoi(m[1]);
          return port.has_value() || !child_.running();
        },
        timeout_s);
    return port;
  }

  // SIGTERM and wait (navemu stops at its next wake-up and prints its summary).
  std::optional<int> stop(double grace_s = 3.0) { return child_.stop(grace_s); }
  // The same, checking that navemu exited with status 0 (its summary is then in err()).
  void stop_expecting_exit_0() {
    const std::optional<int> st = stop();
    EXPECT_TRUE(st && WIFEXITED(*st) && WEXITSTATUS(*st) == 0)
        << describe_status(st) << diagnostics();
  }

 private:
  fs::path err_;
  double started_mono_ = 0;
  Child child_;
};

// The number of lines of `text` that contain `what`.
inline int count_lines_with(const std::string& text, const std::string& what) {
  int n = 0;
  std::stringstream ss(text);
  for (std::string line; std::getline(ss, line);) n += line.find(what) != std::string::npos ? 1 : 0;
  return n;
}

// --- A truth stream: datagrams to navemu's UDP port on loopback, counted.
class TruthSender {
 public:
  explicit TruthSender(int port) {
    fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    to_.sin_family = AF_INET;
    to_.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    to_.sin_port = htons(static_cast<std::uint16_t>(port));
  }
  ~TruthSender() {
    if (fd_ >= 0) ::close(fd_);
  }
  TruthSender(const TruthSender&) = delete;
  TruthSender& operator=(const TruthSender&) = delete;
  bool ok() const { return fd_ >= 0; }
  // One datagram at `position` stamped now, plus `offset_s` (a stream that jumped), as host
  // UTC in binary or as GPS time in JSON; returns the time it was sent (CLOCK_REALTIME, s).
  double send(const Geodetic& position, double offset_s = 0.0, bool json_gps_time = false) {
    truth_datagram::Message m;
    m.time_base = json_gps_time ? truth_datagram::TimeBase::kGps : truth_datagram::TimeBase::kHostUtc;
    m.position = {position.lat_deg, position.lon_deg, position.h_m};
    m.sequence = seq_++;
    const double now = real_s();
    const auto unix_ns = static_cast<std::int64_t>(std::llround((now + offset_s) * 1e9));
    m.time_ns = json_gps_time ? gps_from_unix_ns(unix_ns).ns : unix_ns;
    if (json_gps_time) {
      transmit(truth_datagram::encode_json(m));
    } else {
      const auto d = truth_datagram::encode_binary(m);
      transmit(std::string_view(reinterpret_cast<const char*>(d.data()), d.size()));
    }
    return now;
  }
  // One JSON datagram at `position` stamped with GPS time `t` (a simulator's own clock).
  void send_at(const Geodetic& position, GpsTime t) {
    truth_datagram::Message m;
    m.time_base = truth_datagram::TimeBase::kGps;
    m.position = {position.lat_deg, position.lon_deg, position.h_m};
    m.sequence = seq_++;
    m.time_ns = t.ns;
    transmit(truth_datagram::encode_json(m));
  }
  long sent() const { return sent_; }

 private:
  void transmit(std::string_view d) {
    if (::sendto(fd_, d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(&to_), sizeof to_) ==
        static_cast<ssize_t>(d.size()))
      ++sent_;
  }
  int fd_ = -1;
  sockaddr_in to_{};
  std::uint32_t seq_ = 0;
  long sent_ = 0;
};

// --- Reading a pty.

// One line received on the pty, without its CR LF; t_* are the arrival times of its first byte
// (the read(2) that returned it).
struct Received {
  std::string text;
  double t_mono = 0, t_real = 0;
  bool is(const char* type) const {
    return text.size() > 6 && text[0] == '$' && text.compare(3, 3, type) == 0;
  }
};

// A client of the pty: non-blocking reads with poll(2) and a deadline, split into lines.
class PtyReader {
 public:
  ~PtyReader() { close(); }
  bool open(const fs::path& path) {
    close();
    fd_ = ::open(path.c_str(), O_RDONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    line_.clear();
    return fd_ >= 0;
  }
  void close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  bool is_open() const { return fd_ >= 0; }
  // Bytes of a line not yet ended.
  const std::string& partial() const { return line_; }

  // Reads until monotonic time `until` (or, when `max_read` > 0, reads of at most that many
  // bytes); complete lines are appended to `out`. Returns the bytes read.
  std::size_t read_until(double until, std::vector<Received>& out, std::size_t max_read = 0) {
    std::size_t total = 0;
    for (;;) {
      const double left = until - mono_s();
      if (left <= 0 || fd_ < 0) return total;
      pollfd p{fd_, POLLIN, 0};
      const int r = ::poll(&p, 1, static_cast<int>(std::ceil(left * 1000.0)));
      if (r <= 0) continue;
      total += read_once(out, max_read);
    }
  }

  // One read(2) of at most `max_read` bytes once data is there (at most `timeout_s`).
  std::size_t read_some(std::size_t max_read, double timeout_s, std::vector<Received>& out) {
    pollfd p{fd_, POLLIN, 0};
    if (fd_ < 0 || ::poll(&p, 1, static_cast<int>(std::ceil(timeout_s * 1000.0))) <= 0) return 0;
    return read_once(out, max_read);
  }

  // Whatever is waiting now: reads until the pty has nothing more (EAGAIN).
  std::size_t drain(std::vector<Received>& out, std::string* raw = nullptr) {
    std::size_t total = 0;
    for (std::size_t n; (n = read_once(out, 0, raw)) > 0;) total += n;
    return total;
  }

  // Drops what was queued before this client came (it would arrive in one burst).
  void discard_queued() {
    std::vector<Received> stale;
    drain(stale);
  }

 private:
  std::size_t read_once(std::vector<Received>& out, std::size_t max_read, std::string* raw = nullptr) {
    char buf[4096];
    const std::size_t want = max_read > 0 ? std::min(max_read, sizeof buf) : sizeof buf;
    const ssize_t n = ::read(fd_, buf, want);
    if (n <= 0) return 0;
    const double tm = mono_s(), tr = real_s();
    if (raw != nullptr) raw->append(buf, static_cast<std::size_t>(n));
    for (ssize_t i = 0; i < n; ++i) {
      if (line_.empty()) {
        t_mono_ = tm;
        t_real_ = tr;
      }
      line_ += buf[i];
      if (buf[i] == '\n') {
        std::string text = line_;
        while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
        out.push_back({text, t_mono_, t_real_});
        line_.clear();
      }
    }
    return static_cast<std::size_t>(n);
  }

  int fd_ = -1;
  std::string line_;
  double t_mono_ = 0, t_real_ = 0;
};

// --- NMEA fields and times.

// "hhmmss.s" -> milliseconds of the day.
inline std::int64_t nmea_ms_of_day(const std::string& hhmmss) {
  if (hhmmss.size() < 6) return -1;
  const double s = std::stod(hhmmss.substr(4));
  return (std::stoll(hhmmss.substr(0, 2)) * 3600 + std::stoll(hhmmss.substr(2, 2)) * 60) * 1000 +
         std::llround(s * 1000.0);
}

// "ddmm.mmmm","N" -> degrees.
inline double nmea_degrees(const std::string& value, const std::string& hemisphere) {
  const double v = std::stod(value);
  const double deg = std::floor(v / 100.0);
  const double d = deg + (v - 100.0 * deg) / 60.0;
  return hemisphere == "S" || hemisphere == "W" ? -d : d;
}

// Days since 1970-01-01 of a proleptic Gregorian date (H. Hinnant's days_from_civil).
inline std::int64_t days_from_civil(std::int64_t y, unsigned m, unsigned d) {
  y -= m <= 2 ? 1 : 0;
  const std::int64_t era = (y >= 0 ? y : y - 399) / 400;
  const auto yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m > 2 ? m - 3 : m + 9) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<std::int64_t>(doe) - 719468;
}

// gpsd's ISO-8601 "2026-11-22T12:48:00.200Z" -> milliseconds since the Unix epoch; -1 if
// malformed.
inline std::int64_t iso_unix_ms(const std::string& iso) {
  int y = 0, mo = 0, d = 0, h = 0, mi = 0;
  double s = 0;
  if (std::sscanf(iso.c_str(), "%d-%d-%dT%d:%d:%lfZ", &y, &mo, &d, &h, &mi, &s) != 6) return -1;
  const std::int64_t days = days_from_civil(y, static_cast<unsigned>(mo), static_cast<unsigned>(d));
  return ((days * 24 + h) * 60 + mi) * 60'000 + std::llround(s * 1000.0);
}

// An RMC's UTC (fields 1 time, 9 ddmmyy) -> milliseconds since the Unix epoch; -1 if empty.
inline std::int64_t rmc_unix_ms(const std::vector<std::string>& f) {
  if (f.size() < 10 || f[1].size() < 6 || f[9].size() != 6) return -1;
  const std::int64_t days =
      days_from_civil(2000 + std::stoll(f[9].substr(4, 2)),
                      static_cast<unsigned>(std::stoul(f[9].substr(2, 2))),
                      static_cast<unsigned>(std::stoul(f[9].substr(0, 2))));
  return days * 86'400'000 + nmea_ms_of_day(f[1]);
}

// One RMC of a session: its epoch (ms since the Unix epoch), status and position.
struct Rmc {
  std::int64_t unix_ms = 0;
  bool valid = false;  // status A
  Geodetic position;
};

inline std::vector<Rmc> rmcs(const std::vector<Received>& lines) {
  std::vector<Rmc> out;
  for (const Received& r : lines) {
    const auto f = nmea::parse(r.text);
    if (!f || (*f)[0].substr(2) != "RMC") continue;
    Rmc m;
    m.unix_ms = rmc_unix_ms(*f);
    m.valid = (*f)[2] == "A";
    if (m.valid)
      m.position = Geodetic{nmea_degrees((*f)[3], (*f)[4]), nmea_degrees((*f)[5], (*f)[6]), 0.0};
    out.push_back(m);
  }
  return out;
}

// Horizontal distance of a fix from the truth, m.
inline double horizontal_error_m(const Geodetic& fix, const Geodetic& truth) {
  const Vec3 e =
      enu_from_ecef(ecef_from_geodetic(Geodetic{fix.lat_deg, fix.lon_deg, truth.h_m}), truth);
  return std::hypot(e.x(), e.y());
}

// --- gpsd.

// `gpsd -N -n -S PORT -F SOCK -P PIDFILE DEVICE` (TESTING.md) on a free port, in the test's
// folder; started once the device (the pty link) exists.
class Gpsd {
 public:
  // Tries a few free ports (another test may take one between the probe and gpsd's bind).
  bool start(const std::string& gpsd, const TempDir& dir, const fs::path& device, double timeout_s) {
    err_ = dir / "gpsd.stderr";
    for (int attempt = 0; attempt < 3; ++attempt) {
      port_ = free_port(SOCK_STREAM);
      child_.start({gpsd, "-N", "-n", "-S", std::to_string(port_), "-F",
                    (dir / "gpsd.sock").string(), "-P", (dir / "gpsd.pid").string(),
                    device.string()},
                   dir / "gpsd.stdout", err_);
      if (wait_until([&] { return !child_.running() || can_connect(); }, timeout_s) &&
          child_.running())
        return true;
      child_.stop(1.0);
    }
    return false;
  }
  int port() const { return port_; }
  Child& child() { return child_; }
  std::string diagnostics() const {
    return "\n--- gpsd stderr (" + err_.string() + ") ---\n" + tail(slurp(err_)) + "\n---";
  }

 private:
  bool can_connect() const {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = htons(static_cast<std::uint16_t>(port_));
    const bool ok = ::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
    ::close(fd);
    return ok;
  }

  fs::path err_;
  int port_ = -1;
  Child child_;
};

// A watcher on gpsd's socket: ?WATCH={"enable":true,"json":true}, then one JSON object per
// line (gpsd's protocol), parsed with yaml-cpp (JSON is YAML flow syntax).
class GpsdClient {
 public:
  ~GpsdClient() {
    if (fd_ >= 0) ::close(fd_);
  }
  bool connect_and_watch(int port) {
    return connect(port, "?WATCH={\"enable\":true,\"json\":true}\n");
  }
  // Connects and sends `watch` (any ?WATCH, e.g. with "raw":1).
  bool connect(int port, const std::string& watch) {
    fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = htons(static_cast<std::uint16_t>(port));
    if (::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) return false;
    return send(watch);
  }
  // A request on the open connection (?DEVICES;).
  bool send(const std::string& line) {
    return ::send(fd_, line.data(), line.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(line.size());
  }

  // The next object gpsd sends, or none when monotonic time `deadline` comes first (or gpsd
  // closes the connection); lines that are not JSON (the raw:1 hex dumps) are skipped.
  // `arrival_real` gets the arrival time (CLOCK_REALTIME).
  std::optional<YAML::Node> next(double deadline, double* arrival_real = nullptr) {
    for (;;) {
      const std::size_t nl = buf_.find('\n');
      if (nl != std::string::npos) {
        const std::string line = buf_.substr(0, nl);
        buf_.erase(0, nl + 1);
        if (line.empty() || line[0] != '{') continue;
        if (arrival_real != nullptr) *arrival_real = last_real_;
        try {
          return YAML::Load(line);
        } catch (const YAML::Exception&) {
          bad_lines_.push_back(line);
          continue;
        }
      }
      const double left = deadline - mono_s();
      if (left <= 0 || fd_ < 0) return std::nullopt;
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(std::ceil(left * 1000.0))) <= 0) continue;
      char b[8192];
      const ssize_t n = ::recv(fd_, b, sizeof b, 0);
      if (n <= 0) {
        ::close(fd_);
        fd_ = -1;
        return std::nullopt;
      }
      last_real_ = real_s();
      buf_.append(b, static_cast<std::size_t>(n));
    }
  }
  const std::vector<std::string>& bad_lines() const { return bad_lines_; }

 private:
  int fd_ = -1;
  std::string buf_;
  double last_real_ = 0;
  std::vector<std::string> bad_lines_;
};

// A string member of a gpsd object, or "".
inline std::string str(const YAML::Node& n, const char* key) {
  return n[key] && n[key].IsScalar() ? n[key].as<std::string>() : std::string{};
}
inline std::optional<double> num(const YAML::Node& n, const char* key) {
  if (!n[key] || !n[key].IsScalar()) return std::nullopt;
  try {
    return n[key].as<double>();
  } catch (const YAML::Exception&) {
    return std::nullopt;
  }
}

}  // namespace navemu::test::clients
