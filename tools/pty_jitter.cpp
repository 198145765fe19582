// navemu-pty-jitter: how punctually a running `navemu run` delivers its epochs on a pty, next
// to what the operating system allows on the same machine at the same moment.
//
// A reader opens the pty (or any device or FIFO carrying NMEA), drops what was queued before
// it came, and time-stamps the arrival of every epoch's first sentence (RMC by default: the
// first sentence of each epoch in navemu's profiles) on CLOCK_REALTIME and CLOCK_MONOTONIC.
// From the monotonic stamps: the gaps between epochs. From the real-time stamps: lateness
// against the ideal grid, lateness = arrival - (the sentence's UTC time + the profile's output
// latency), since navemu's deadline for an epoch is its GPS time plus the latency, and a run
// that starts "now" ties GPS time to the system clock (emulator/engine.hpp).
//
// In the same run a second thread sleeps with clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME)
// on a grid of the same rate and records how late it wakes: the floor any user-space writer
// meets here. TESTING.md: on these shared machines bare clock_nanosleep wake-ups show p99
// lateness of 0.5-3 ms, and a pty writer with absolute deadlines about 0.5 ms sd at an idle
// reader, ~18 ms max with both cores busy; so jitter is reported against this baseline rather
// than against fixed numbers. --load adds a busy thread pinned to the last CPU.

#include <CLI/CLI.hpp>
#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <pthread.h>
#include <sched.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "protocols/nmea.hpp"

namespace {

constexpr std::int64_t kNsPerS = 1'000'000'000;

std::int64_t now_ns(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * kNsPerS + ts.tv_nsec;
}

// Days since 1970-01-01 of a Gregorian date (H. Hinnant's days_from_civil).
std::int64_t days_from_civil(std::int64_t y, unsigned m, unsigned d) {
  y -= m <= 2 ? 1 : 0;
  const std::int64_t era = (y >= 0 ? y : y - 399) / 400;
  const auto yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m > 2 ? m - 3 : m + 9) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<std::int64_t>(doe) - 719468;
}

// The UTC of a sentence's time field "hhmmss.ss", in ns since the Unix epoch. RMC carries its
// date (field 9, ddmmyy); other sentences take the day that puts the time nearest `arrival_ns`.
std::optional<std::int64_t> sentence_utc_ns(const std::vector<std::string>& f, std::int64_t arrival_ns) {
  // The time is field 1 of RMC, GGA, GNS, ZDA, GST (GLL: field 5).
  const std::size_t time_field = f[0].size() >= 3 && f[0].substr(f[0].size() - 3) == "GLL" ? 5 : 1;
  if (f.size() <= time_field || f[time_field].size() < 6) return std::nullopt;
  const std::string& t = f[time_field];
  const double sec = std::strtod(t.c_str() + 4, nullptr);
  const std::int64_t tod_ns =
      (std::stoll(t.substr(0, 2)) * 3600 + std::stoll(t.substr(2, 2)) * 60) * kNsPerS +
      std::llround(sec * 1e9);
  const std::string type = f[0].size() >= 3 ? f[0].substr(f[0].size() - 3) : "";
  if (type == "RMC" && f.size() > 9 && f[9].size() == 6) {
    const std::int64_t days = days_from_civil(2000 + std::stoll(f[9].substr(4, 2)),
                                              static_cast<unsigned>(std::stoul(f[9].substr(2, 2))),
                                              static_cast<unsigned>(std::stoul(f[9].substr(0, 2))));
    return days * 86400 * kNsPerS + tod_ns;
  }
  const std::int64_t day_ns = 86400 * kNsPerS;
  std::int64_t base = arrival_ns / day_ns * day_ns + tod_ns;
  if (base - arrival_ns > day_ns / 2) base -= day_ns;
  if (arrival_ns - base > day_ns / 2) base += day_ns;
  return base;
}

struct Stats {
  std::size_t n = 0;
  double mean = 0, min = 0, p50 = 0, p99 = 0, max = 0;
};

Stats stats(std::vector<double> v) {
  Stats s;
  s.n = v.size();
  if (v.empty()) return s;
  double sum = 0;
  for (double x : v) sum += x;
  s.mean = sum / static_cast<double>(v.size());
  std::sort(v.begin(), v.end());
  const auto pct = [&](double p) {
    const auto k = static_cast<std::size_t>(std::ceil(p * static_cast<double>(v.size()))) - 1;
    return v[std::min(v.size() - 1, k)];
  };
  s.min = v.front();
  s.p50 = pct(0.50);
  s.p99 = pct(0.99);
  s.max = v.back();
  return s;
}

// A profile's rate_hz and output_latency_s from its YAML (configs/gnss/NAME.yaml): plain
// "key: value" lines, enough for these two keys without a YAML library.
bool read_profile(const std::string& path, double& rate_hz, double& latency_s) {
  std::ifstream in(path);
  if (!in) return false;
  for (std::string line; std::getline(in, line);) {
    const auto value = [&](const char* key) -> std::optional<double> {
      const std::string k = std::string(key) + ":";
      if (line.rfind(k, 0) != 0) return std::nullopt;
      return std::strtod(line.c_str() + k.size(), nullptr);
    };
    if (const auto r = value("rate_hz")) rate_hz = *r;
    if (const auto l = value("output_latency_s")) latency_s = *l;
  }
  return true;
}

std::atomic<bool> g_done{false};

// The OS floor: absolute-deadline sleeps on the monotonic clock, wake-up lateness in ms.
void bare_timer(std::int64_t period_ns, std::int64_t end_mono_ns, std::vector<double>& late_ms) {
  std::int64_t next = (now_ns(CLOCK_MONOTONIC) / period_ns + 1) * period_ns;
  while (next < end_mono_ns) {
    const timespec ts{static_cast<time_t>(next / kNsPerS), static_cast<long>(next % kNsPerS)};
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
    late_ms.push_back(static_cast<double>(now_ns(CLOCK_MONOTONIC) - next) * 1e-6);
    next += period_ns;
  }
}

// A thread that spins, pinned to one CPU: a busy neighbour for --load.
void spin(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(static_cast<std::size_t>(cpu), &set);
  pthread_setaffinity_np(pthread_self(), sizeof set, &set);
  volatile std::uint64_t x = 0;
  while (!g_done.load(std::memory_order_relaxed)) x = x + 1;
}

}  // namespace

int main(int argc, char** argv) {
  std::string path, sentence = "RMC", profile, csv_path;
  double duration_s = 30.0, latency_s = 0.05, rate_hz = 5.0;
  bool load = false;
  CLI::App app{"Measures the arrival jitter of a running navemu's epochs on a pty against a bare "
               "clock_nanosleep timer in the same run"};
  app.footer(
      "Reads PATH (navemu's pty link, e.g. /tmp/navemu-gnss, or /dev/pts/N as its start-up line\n"
      "says) for --duration seconds. Each epoch's first sentence (--sentence, default RMC) is\n"
      "time-stamped on arrival with CLOCK_REALTIME and CLOCK_MONOTONIC:\n"
      "  gap       monotonic time between consecutive arrivals (ideal: 1 / rate)\n"
      "  lateness  arrival (realtime) - (the sentence's UTC time + the profile's latency)\n"
      "Meanwhile a second thread sleeps to absolute deadlines (clock_nanosleep TIMER_ABSTIME,\n"
      "CLOCK_MONOTONIC) on a --rate grid and records its wake-up lateness: the OS floor. The\n"
      "table gives count, gap mean/p50/p99/max and lateness min/p50/p99/max for both, and\n"
      "navemu's lateness over the timer's. navemu's lateness also holds its fixed start-up\n"
      "offset (GPS time is tied to the system clock once, at start) and the reader's own wake-up.\n"
      "Run navemu with a start of 'now' (the default), e.g.:\n"
      "  navemu run & navemu-pty-jitter /tmp/navemu-gnss --duration 30\n"
      "  navemu-pty-jitter /tmp/navemu-gnss --profile configs/gnss/ublox-nmea-5hz.yaml --load");
  app.add_option("path", path, "The pty (or device) navemu writes to")->required();
  app.add_option("--duration", duration_s, "Seconds to measure (default 30)")
      ->check(CLI::PositiveNumber);
  app.add_option("--sentence", sentence,
                 "Sentence type that starts an epoch, without talker (default RMC)");
  app.add_option("--latency", latency_s,
                 "The profile's output_latency_s, seconds (default 0.05: garmin-18x-5hz)");
  app.add_option("--rate", rate_hz, "Epochs per second, for the timer grid (default 5)")
      ->check(CLI::PositiveNumber);
  app.add_option("--profile", profile,
                 "A GNSS profile YAML (configs/gnss/*.yaml): takes --rate and --latency from it");
  app.add_option("--csv", csv_path,
                 "Also write every arrival: mono_ns,real_ns,utc_ns,lateness_ms,gap_ms");
  app.add_flag("--load", load, "Spin a busy thread pinned to the last CPU meanwhile");
  CLI11_PARSE(app, argc, argv);
  if (!profile.empty() && !read_profile(profile, rate_hz, latency_s)) {
    fmt::print(stderr, "navemu-pty-jitter: cannot read profile {}\n", profile);
    return 2;
  }

  const int fd = ::open(path.c_str(), O_RDONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    fmt::print(stderr, "navemu-pty-jitter: {}: {}\n", path, std::strerror(errno));
    return 2;
  }
  // What was queued before this reader came would arrive as a burst: drop it.
  char buf[4096];
  while (::read(fd, buf, sizeof buf) > 0) {
  }

  const auto period_ns = static_cast<std::int64_t>(std::llround(1e9 / rate_hz));
  const std::int64_t end_mono = now_ns(CLOCK_MONOTONIC) + std::llround(duration_s * 1e9);
  std::vector<double> timer_late_ms;
  timer_late_ms.reserve(static_cast<std::size_t>(duration_s * rate_hz) + 16);
  std::thread timer(bare_timer, period_ns, end_mono, std::ref(timer_late_ms));
  std::thread loader;
  const long ncpu = ::sysconf(_SC_NPROCESSORS_ONLN);
  if (load) loader = std::thread(spin, static_cast<int>(std::max(0L, ncpu - 1)));

  struct Arrival {
    std::int64_t mono_ns, real_ns, utc_ns;
  };
  std::vector<Arrival> arrivals;
  std::size_t bad = 0;
  std::string line;
  std::int64_t line_mono = 0, line_real = 0;
  bool skip_first_fragment = true;  // a sentence cut by the drain above
  for (;;) {
    const std::int64_t left = end_mono - now_ns(CLOCK_MONOTONIC);
    if (left <= 0) break;
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left / 1'000'000 + 1)) <= 0) continue;
    const ssize_t n = ::read(fd, buf, sizeof buf);
    const std::int64_t tm = now_ns(CLOCK_MONOTONIC), tr = now_ns(CLOCK_REALTIME);
    if (n <= 0) {
      if (n == 0 || (errno != EAGAIN && errno != EINTR)) break;
      continue;
    }
    for (ssize_t i = 0; i < n; ++i) {
      if (line.empty()) {
        line_mono = tm;
        line_real = tr;
      }
      line += buf[i];
      if (buf[i] != '\n') continue;
      const bool fragment = skip_first_fragment && line[0] != '$';
      skip_first_fragment = false;
      if (!fragment) {
        const auto f = navemu::nmea::parse(line);
        if (!f) {
          ++bad;
        } else if ((*f)[0].size() >= sentence.size() &&
                   (*f)[0].compare((*f)[0].size() - sentence.size(), sentence.size(), sentence) == 0) {
          if (const auto utc = sentence_utc_ns(*f, line_real))
            arrivals.push_back({line_mono, line_real, *utc});
        }
      }
      line.clear();
    }
  }
  ::close(fd);
  timer.join();
  g_done.store(true);
  if (loader.joinable()) loader.join();

  std::vector<double> gaps_ms, late_ms;
  std::size_t missing = 0;
  const auto latency_ns = std::llround(latency_s * 1e9);
  for (std::size_t i = 0; i < arrivals.size(); ++i) {
    late_ms.push_back(static_cast<double>(arrivals[i].real_ns - (arrivals[i].utc_ns + latency_ns)) * 1e-6);
    if (i == 0) continue;
    gaps_ms.push_back(static_cast<double>(arrivals[i].mono_ns - arrivals[i - 1].mono_ns) * 1e-6);
    const std::int64_t steps = std::llround(static_cast<double>(arrivals[i].utc_ns - arrivals[i - 1].utc_ns) /
                                            static_cast<double>(period_ns));
    if (steps > 1) missing += static_cast<std::size_t>(steps - 1);
  }
  if (!csv_path.empty()) {
    std::ofstream csv(csv_path);
    csv << "mono_ns,real_ns,utc_ns,lateness_ms,gap_ms\n";
    for (std::size_t i = 0; i < arrivals.size(); ++i)
      csv << fmt::format("{},{},{},{:.4f},{}\n", arrivals[i].mono_ns, arrivals[i].real_ns,
                         arrivals[i].utc_ns, late_ms[i], i ? fmt::format("{:.4f}", gaps_ms[i - 1]) : "");
  }

  // The timer's "gap" is its period plus the difference of consecutive lateness values.
  std::vector<double> timer_gaps_ms;
  for (std::size_t i = 1; i < timer_late_ms.size(); ++i)
    timer_gaps_ms.push_back(static_cast<double>(period_ns) * 1e-6 + timer_late_ms[i] - timer_late_ms[i - 1]);
  const Stats g = stats(gaps_ms), l = stats(late_ms);
  const Stats tg = stats(timer_gaps_ms), tl = stats(timer_late_ms);

  fmt::print("navemu-pty-jitter: {} for {:.1f} s, first sentence {}, latency {:.1f} ms, grid {} Hz "
             "({:.1f} ms), load {}, {} CPUs\n",
             path, duration_s, sentence, latency_s * 1e3, rate_hz, static_cast<double>(period_ns) * 1e-6,
             load ? "on" : "off", ncpu);
  fmt::print("{:<20} {:>6} | {:>9} {:>9} {:>9} {:>9} | {:>9} {:>9} {:>9} {:>9}\n", "ms", "count",
             "gap mean", "gap p50", "gap p99", "gap max", "late min", "late p50", "late p99",
             "late max");
  const auto row = [](const char* name, const Stats& gs, const Stats& ls) {
    fmt::print("{:<20} {:>6} | {:>9.3f} {:>9.3f} {:>9.3f} {:>9.3f} | {:>9.3f} {:>9.3f} {:>9.3f} {:>9.3f}\n",
               name, ls.n, gs.mean, gs.p50, gs.p99, gs.max, ls.min, ls.p50, ls.p99, ls.max);
  };
  row(fmt::format("navemu ({})", sentence).c_str(), g, l);
  row("bare timer", tg, tl);
  const auto ratio = [](double a, double b) {
    return b > 0 ? fmt::format("{:>9.1f}", a / b) : fmt::format("{:>9}", "-");
  };
  fmt::print("{:<20} {:>6} | {:>9} {:>9} {:>9} {:>9} | {:>9} {} {} {}\n", "ratio navemu/timer", "",
             "", "", "", "", "", ratio(l.p50, tl.p50), ratio(l.p99, tl.p99), ratio(l.max, tl.max));
  // navemu's minimum lateness is mostly a fixed offset (its clock's anchoring at start and the
  // pipeline's constant part); what varies above it is the jitter to compare with the timer's.
  fmt::print("navemu lateness minus its minimum (the fixed offset): p50 {:.3f} p99 {:.3f} max {:.3f} ms "
             "(p99 {:.1f}x the timer's); {} epochs missing, {} bad sentences\n",
             l.p50 - l.min, l.p99 - l.min, l.max - l.min,
             tl.p99 > 0 ? (l.p99 - l.min) / tl.p99 : 0.0, missing, bad);
  return arrivals.size() >= 2 ? 0 : 1;
}
