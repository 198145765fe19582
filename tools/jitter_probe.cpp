// navemu-jitter: how punctually a running `navemu run` delivers its GNSS epochs on a pty and
// its IMU samples on SocketCAN, next to what the operating system allows on the same machine
// at the same moment.
//
// Streams (either or both):
// - pty: a reader opens the pty, drops what was queued before it came, and time-stamps the
//   arrival of every epoch's first sentence (RMC by default: the first sentence of each epoch
//   in navemu's profiles). The epoch's time is the sentence's UTC time.
// - can: a raw CAN socket (CAN FD enabled, filtered to navemu's high-resolution identifiers,
//   protocols/can_frames.hpp section 2) time-stamps the first frame of every sample: HR_TIME of
//   the five classic frames, or the one HR_FD frame. The sample is decoded (order and CRC
//   checked) by the project's decoder; its time is the GPS time it carries. The kernel's receive
//   stamp of that frame (SO_TIMESTAMPNS) is kept too: on vcan it is when navemu's write reached
//   the interface, so it shows navemu's own lateness without this reader's wake-up.
// Every arrival is stamped on CLOCK_MONOTONIC and CLOCK_REALTIME. From the monotonic stamps: the
// gaps between epochs. From the real-time stamps: lateness against the ideal grid,
//   lateness = arrival - (the epoch's time as Unix time + the profile's output latency),
// since navemu's deadline for an epoch is its GPS time plus the latency (emulator/engine.hpp;
// for the IMU, emulator/imu_can.cpp sends a sample's frames back to back at that deadline), and
// a run that starts "now" ties GPS time to the system clock. GPS time becomes Unix time with
// the leap seconds of core/time.hpp.
//
// In the same run a floor thread sleeps with clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME) on
// a grid at the highest rate of the streams measured and records how late it wakes: the floor
// any user-space writer meets here. ../shared/TESTING.md: on these shared machines bare
// clock_nanosleep wake-ups show p99 lateness of 0.5-3 ms, and a pty writer with absolute
// deadlines about 0.5 ms sd at an idle reader, ~18 ms max with both cores busy; so jitter is
// reported against this floor rather than against fixed numbers, and nothing passes or fails
// on timing. --load adds a busy thread pinned to the last CPU.

#include <CLI/CLI.hpp>
#include <fcntl.h>
#include <fmt/format.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <pthread.h>
#include <sched.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "emulator/imu_profile.hpp"
#include "emulator/run_config.hpp"
#include "core/time.hpp"
#include "protocols/can_frames.hpp"
#include "protocols/nmea.hpp"

namespace {

using navemu::kNsPerS;

std::int64_t now_ns(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * kNsPerS + ts.tv_nsec;
}

// The UTC of a sentence's time field "hhmmss.ss", in ns since the Unix epoch. RMC carries its
// date (field 9, ddmmyy); other sentences take the day that puts the time nearest `arrival_ns`.
std::optional<std::int64_t> sentence_utc_ns(const std::vector<std::string>& f,
                                            std::int64_t arrival_ns) {
  // The time is field 1 of RMC, GGA, GNS, ZDA, GST (GLL: field 5).
  const std::string type = f[0].size() >= 3 ? f[0].substr(f[0].size() - 3) : "";
  const std::size_t time_field = type == "GLL" ? 5 : 1;
  if (f.size() <= time_field || f[time_field].size() < 6) return std::nullopt;
  const std::string& t = f[time_field];
  const double sec = std::strtod(t.c_str() + 4, nullptr);
  const std::int64_t tod_ns =
      (std::stoll(t.substr(0, 2)) * 3600 + std::stoll(t.substr(2, 2)) * 60) * kNsPerS +
      std::llround(sec * 1e9);
  if (type == "RMC" && f.size() > 9 && f[9].size() == 6) {
    const navemu::CalendarTime midnight{2000 + std::stoi(f[9].substr(4, 2)),
                                        std::stoi(f[9].substr(2, 2)), std::stoi(f[9].substr(0, 2)),
                                        0, 0, 0.0};
    return navemu::unix_ns_from_gps(navemu::gps_from_utc(midnight)) + tod_ns;
  }
  const std::int64_t day_ns = 86400 * kNsPerS;
  std::int64_t base = arrival_ns / day_ns * day_ns + tod_ns;
  if (base - arrival_ns > day_ns / 2) base -= day_ns;
  if (arrival_ns - base > day_ns / 2) base += day_ns;
  return base;
}

struct Stats {
  std::size_t n = 0;
  double min = 0, p50 = 0, p99 = 0, max = 0;
};

// Nearest-rank percentiles.
Stats stats(std::vector<double> v) {
  Stats s;
  s.n = v.size();
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  const auto pct = [&](double p) {
    const auto k = static_cast<std::size_t>(std::ceil(p * static_cast<double>(v.size())));
    return v[std::min(v.size() - 1, k > 0 ? k - 1 : 0)];
  };
  s.min = v.front();
  s.p50 = pct(0.50);
  s.p99 = pct(0.99);
  s.max = v.back();
  return s;
}

// One epoch or sample as the reader saw it. `due_unix_ns` is its deadline on the Unix time
// scale; `kernel_real_ns` the kernel's receive stamp (CAN only, 0 when absent).
struct Arrival {
  std::int64_t mono_ns = 0, real_ns = 0, kernel_real_ns = 0;
  std::int64_t epoch_ns = 0;  // the epoch's own time (UTC or GPS ns), for missing epochs
  std::int64_t due_unix_ns = 0;
};

// ---- pty: NMEA epochs -------------------------------------------------------------------------

struct PtyReader {
  std::string path, sentence;
  std::int64_t latency_ns = 0, period_ns = 0;
  int fd = -1;
  bool open = false;
  std::string line;
  std::int64_t line_mono = 0, line_real = 0;
  bool skip_first_fragment = true;  // a sentence cut by the initial drain
  std::size_t bad = 0;
  std::vector<Arrival> arrivals;

  void start() {
    fd = ::open(path.c_str(), O_RDONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) throw std::runtime_error(fmt::format("pty {}: {}", path, std::strerror(errno)));
    open = true;
    // What was queued before this reader came would arrive as a burst: drop it.
    char buf[4096];
    for (int i = 0; i < 64 && ::read(fd, buf, sizeof buf) > 0; ++i) {
    }
  }

  // Reads what is there; false once the writer has gone (EOF or EIO after a hang-up).
  bool on_readable() {
    char buf[4096];
    const ssize_t n = ::read(fd, buf, sizeof buf);
    const int err = errno;
    const std::int64_t tm = now_ns(CLOCK_MONOTONIC), tr = now_ns(CLOCK_REALTIME);
    if (n <= 0) return n < 0 && (err == EAGAIN || err == EINTR);
    for (ssize_t i = 0; i < n; ++i) {
      if (line.empty()) {
        line_mono = tm;
        line_real = tr;
      }
      line += buf[i];
      if (buf[i] == '\n') end_of_line();
    }
    return true;
  }

  void end_of_line() {
    const bool fragment = skip_first_fragment && line[0] != '$';
    skip_first_fragment = false;
    if (!fragment) {
      const auto f = navemu::nmea::parse(line);
      if (!f) {
        ++bad;
      } else if ((*f)[0].size() >= sentence.size() &&
                 (*f)[0].compare((*f)[0].size() - sentence.size(), sentence.size(), sentence) ==
                     0) {
        if (const auto utc = sentence_utc_ns(*f, line_real))
          arrivals.push_back({line_mono, line_real, 0, *utc, *utc + latency_ns});
      }
    }
    line.clear();
  }
};

// ---- SocketCAN: navemu high-resolution samples ------------------------------------------------

struct CanReader {
  std::string iface;
  navemu::can::highres::Config layout;
  std::int64_t latency_ns = 0, period_ns = 0;
  int sock = -1;
  bool open = false;
  std::size_t bad = 0;             // frames out of order, or samples failing their CRC
  std::uint32_t socket_drops = 0;  // frames the kernel dropped for this socket (SO_RXQ_OVFL)
  std::vector<Arrival> arrivals;

  // The classic frames of the sample being assembled, and how its first frame arrived.
  std::array<navemu::can::CanFrame, navemu::can::highres::kClassicFrameCount> pending{};
  std::size_t pending_n = 0;
  Arrival pending_first;
  std::int64_t last_gps_ns = -1;

  std::string fail(const char* what) const {
    return fmt::format("can {}: {}: {}", iface, what, std::strerror(errno));
  }

  void start() {
    sock = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
    if (sock < 0) {
      if (errno == EAFNOSUPPORT || errno == EPROTONOSUPPORT)
        throw std::runtime_error(
            fmt::format("can {}: this kernel has no SocketCAN (socket(AF_CAN): {}); run inside "
                        "tools/run-in-uml, which provides vcan0",
                        iface, std::strerror(errno)));
      throw std::runtime_error(fail("socket(AF_CAN)"));
    }
    if (iface.empty() || iface.size() >= IFNAMSIZ)
      throw std::runtime_error(fmt::format("can {}: no such interface", iface));
    ifreq ifr{};
    std::memcpy(ifr.ifr_name, iface.c_str(), iface.size() + 1);
    if (::ioctl(sock, SIOCGIFINDEX, &ifr) != 0) {
      if (errno == ENODEV)
        throw std::runtime_error(fmt::format("can {}: no such interface", iface));
      throw std::runtime_error(fail("SIOCGIFINDEX"));
    }
    const int index = ifr.ifr_ifindex;
    const int on = 1;
    // CAN FD frames too (highres-fd), can.rst "RAW socket option CAN_RAW_FD_FRAMES".
    if (::setsockopt(sock, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &on, sizeof on) != 0)
      throw std::runtime_error(fail("CAN_RAW_FD_FRAMES"));
    // Only navemu's high-resolution identifiers: the five classic frames and the FD frame.
    const canid_t flag = layout.extended ? CAN_EFF_FLAG : 0;
    const canid_t mask =
        (layout.extended ? CAN_EFF_MASK : CAN_SFF_MASK) | CAN_EFF_FLAG | CAN_RTR_FLAG;
    std::vector<can_filter> filters;
    for (std::uint32_t off = 0; off < navemu::can::highres::kClassicFrameCount; ++off)
      filters.push_back({(layout.base_id + off) | flag, mask});
    filters.push_back({(layout.base_id + navemu::can::highres::kOffsetFd) | flag, mask});
    if (::setsockopt(sock, SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(),
                     static_cast<socklen_t>(filters.size() * sizeof(can_filter))) != 0)
      throw std::runtime_error(fail("CAN_RAW_FILTER"));
    // Kernel receive stamps, and the count of frames dropped for a full receive queue. The queue
    // is made large (seconds of a 1 kHz IMU) so that a reader stalled by --load loses nothing;
    // SO_RCVBUFFORCE needs CAP_NET_ADMIN, SO_RCVBUF is capped by net.core.rmem_max.
    if (::setsockopt(sock, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on) != 0)
      throw std::runtime_error(fail("SO_TIMESTAMPNS"));
    if (::setsockopt(sock, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof on) != 0)
      throw std::runtime_error(fail("SO_RXQ_OVFL"));
    const int rcvbuf = 8 << 20;
    if (::setsockopt(sock, SOL_SOCKET, SO_RCVBUFFORCE, &rcvbuf, sizeof rcvbuf) != 0)
      (void)::setsockopt(sock, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
    sockaddr_can addr{};
    addr.can_family = AF_CAN;
    addr.can_ifindex = index;
    if (::bind(sock, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0)
      throw std::runtime_error(fail("bind"));
    open = true;
  }

  // Reads every queued frame, in batches; false on a socket error (interface gone).
  bool on_readable() {
    constexpr std::size_t kBatch = 64;
    constexpr std::size_t kControl =
        CMSG_SPACE(sizeof(timespec)) + CMSG_SPACE(sizeof(std::uint32_t));
    std::array<canfd_frame, kBatch> frames{};
    std::array<iovec, kBatch> iov{};
    std::array<mmsghdr, kBatch> msgs{};
    std::array<std::array<char, kControl>, kBatch> control{};
    for (int round = 0; round < 64; ++round) {  // bounded: at most 4096 frames per wake-up
      for (std::size_t i = 0; i < kBatch; ++i) {
        iov[i] = {&frames[i], sizeof(canfd_frame)};
        msgs[i] = {};
        msgs[i].msg_hdr.msg_iov = &iov[i];
        msgs[i].msg_hdr.msg_iovlen = 1;
        msgs[i].msg_hdr.msg_control = control[i].data();
        msgs[i].msg_hdr.msg_controllen = kControl;
      }
      const int n = ::recvmmsg(sock, msgs.data(), kBatch, MSG_DONTWAIT, nullptr);
      const int err = errno;
      const std::int64_t tm = now_ns(CLOCK_MONOTONIC), tr = now_ns(CLOCK_REALTIME);
      if (n < 0) return err == EAGAIN || err == EWOULDBLOCK || err == EINTR;
      for (int i = 0; i < n; ++i) {
        const auto k = static_cast<std::size_t>(i);
        std::int64_t kernel_ns = 0;
        for (cmsghdr* c = CMSG_FIRSTHDR(&msgs[k].msg_hdr); c != nullptr;
             c = CMSG_NXTHDR(&msgs[k].msg_hdr, c)) {
          if (c->cmsg_level != SOL_SOCKET) continue;
          if (c->cmsg_type == SO_TIMESTAMPNS) {
            timespec ts{};
            std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
            kernel_ns = static_cast<std::int64_t>(ts.tv_sec) * kNsPerS + ts.tv_nsec;
          } else if (c->cmsg_type == SO_RXQ_OVFL) {
            std::memcpy(&socket_drops, CMSG_DATA(c), sizeof socket_drops);
          }
        }
        on_frame(frames[k], msgs[k].msg_len == CANFD_MTU, Arrival{tm, tr, kernel_ns, 0, 0});
      }
      if (n < static_cast<int>(kBatch)) break;
    }
    return true;
  }

  void on_frame(const canfd_frame& raw, bool fd, const Arrival& stamp) {
    namespace hr = navemu::can::highres;
    navemu::can::CanFrame f;
    f.extended = (raw.can_id & CAN_EFF_FLAG) != 0;
    f.id = raw.can_id & (f.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
    f.fd = fd;
    f.len = std::min(raw.len, static_cast<std::uint8_t>(fd ? 64 : 8));
    std::memcpy(f.data.data(), raw.data, f.len);
    const std::uint32_t off = f.id - layout.base_id;
    if (fd && off == hr::kOffsetFd) {
      if (const auto d = hr::decode_fd(f, layout))
        record(*d, stamp);
      else
        ++bad;
      return;
    }
    if (off == hr::kOffsetTime) {  // the first frame of a classic sample
      if (pending_n != 0) ++bad;   // the previous sample never completed
      pending_n = 0;
      pending_first = stamp;
    } else if (off != pending_n) {  // out of order, or its HR_TIME was lost
      if (pending_n != 0) ++bad;
      pending_n = 0;
      return;
    }
    pending[pending_n++] = f;
    if (pending_n < hr::kClassicFrameCount) return;
    pending_n = 0;
    if (const auto d = hr::decode_classic(pending, layout))
      record(*d, pending_first);
    else
      ++bad;
  }

  // The first arrival of each sample: a sample sent in both layouts (highres and highres-fd) is
  // recorded once, at whichever frame came first.
  void record(const navemu::can::highres::Decoded& d, Arrival a) {
    if (d.gps_time_ns == last_gps_ns) return;
    last_gps_ns = d.gps_time_ns;
    a.epoch_ns = d.gps_time_ns;
    a.due_unix_ns = navemu::unix_ns_from_gps(navemu::GpsTime{d.gps_time_ns}) + latency_ns;
    arrivals.push_back(a);
  }
};

// ---- the floor and the load -------------------------------------------------------------------

std::atomic<bool> g_done{false};

// The OS floor: absolute-deadline sleeps on the monotonic clock, wake-up lateness in ms.
void floor_timer(std::int64_t period_ns, std::int64_t end_mono_ns, std::vector<double>& late_ms) {
  std::int64_t next = (now_ns(CLOCK_MONOTONIC) / period_ns + 1) * period_ns;
  while (next < end_mono_ns && !g_done.load(std::memory_order_relaxed)) {
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

// ---- results ----------------------------------------------------------------------------------

struct Row {
  std::string name;
  std::size_t missing = 0;
  Stats gap, late;
  bool is_floor = false;
};

// Gaps, lateness and missing epochs of one stream. `kernel` takes the kernel's receive stamps
// in place of the reader's (the gaps then come from the real-time stamps).
Row stream_row(std::string name, const std::vector<Arrival>& arr, std::int64_t period_ns,
               bool kernel) {
  std::vector<double> gaps_ms, late_ms;
  Row r;
  r.name = std::move(name);
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const std::int64_t at = kernel ? arr[i].kernel_real_ns : arr[i].real_ns;
    late_ms.push_back(static_cast<double>(at - arr[i].due_unix_ns) * 1e-6);
    if (i == 0) continue;
    gaps_ms.push_back(kernel ? static_cast<double>(at - arr[i - 1].kernel_real_ns) * 1e-6
                             : static_cast<double>(arr[i].mono_ns - arr[i - 1].mono_ns) * 1e-6);
    const std::int64_t steps = (arr[i].epoch_ns - arr[i - 1].epoch_ns + period_ns / 2) / period_ns;
    if (steps > 1) r.missing += static_cast<std::size_t>(steps - 1);
  }
  r.gap = stats(gaps_ms);
  r.late = stats(late_ms);
  return r;
}

// A stream's p99 lateness over the floor's; `above_min`: its p99 above its own minimum (the
// fixed offset between navemu's GPS time and the system clock, taken once at its start, plus
// the pipeline's constant part), which leaves the jitter alone.
std::string ratio(const Row& r, const Row& floor, bool above_min) {
  if (r.is_floor || floor.late.p99 <= 0 || r.late.n == 0) return "-";
  return fmt::format("{:.1f}", (r.late.p99 - (above_min ? r.late.min : 0.0)) / floor.late.p99);
}

void print_table(const std::vector<Row>& rows) {
  const Row& floor = rows.back();
  fmt::print("{:<34} {:>6} {:>7} | {:>8} {:>8} {:>8} | {:>8} {:>8} {:>8} {:>8} | {:>9} {:>9}\n",
             "ms", "count", "missing", "gap p50", "gap p99", "gap max", "late min", "late p50",
             "late p99", "late max", "p99/floor", "-min/fl.");
  for (const Row& r : rows)
    fmt::print(
        "{:<34} {:>6} {:>7} | {:>8.3f} {:>8.3f} {:>8.3f} | {:>8.3f} {:>8.3f} {:>8.3f} {:>8.3f} | "
        "{:>9} {:>9}\n",
        r.name, r.late.n, r.is_floor ? "-" : fmt::format("{}", r.missing), r.gap.p50, r.gap.p99,
        r.gap.max, r.late.min, r.late.p50, r.late.p99, r.late.max, ratio(r, floor, false),
        ratio(r, floor, true));
}

std::string markdown_table(const std::string& caption, const std::vector<Row>& rows) {
  const Row& floor = rows.back();
  std::string s = caption + "\n\n";
  s += "| stream | count | missing | gap p50 ms | gap p99 ms | gap max ms | late min ms | "
       "late p50 ms | late p99 ms | late max ms | p99 / floor p99 | (p99 - min) / floor p99 |\n";
  s += "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const Row& r : rows)
    s += fmt::format(
        "| {} | {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {} | {} "
        "|\n",
        r.name, r.late.n, r.is_floor ? "-" : fmt::format("{}", r.missing), r.gap.p50, r.gap.p99,
        r.gap.max, r.late.min, r.late.p50, r.late.p99, r.late.max, ratio(r, floor, false),
        ratio(r, floor, true));
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  PtyReader pty;
  CanReader can;
  pty.sentence = "RMC";
  std::string gnss_profile = "garmin-18x-5hz", imu_profile = "paper_phidget";
  std::string markdown_path, csv_path;
  double seconds = 30.0;
  bool load = false;
  std::uint32_t base_id = can.layout.base_id;
  CLI::App app{
      "navemu-jitter: the arrival jitter of a running navemu's GNSS epochs (pty) and IMU "
      "samples (SocketCAN) against a bare clock_nanosleep timer in the same run"};
  app.footer(
      "Measures for --seconds. Each epoch's arrival is stamped with CLOCK_MONOTONIC and\n"
      "CLOCK_REALTIME:\n"
      "  --pty PATH   navemu's pty (its link, e.g. /tmp/navemu-gnss): the first sentence of each\n"
      "               epoch (--sentence, default RMC); the epoch time is its UTC time.\n"
      "  --can IFACE  a SocketCAN interface carrying navemu's highres or highres-fd layout\n"
      "               (configs/can/navemu.dbc): the first frame of each sample; the epoch time\n"
      "               is the GPS time in the sample. A second row gives the kernel's receive\n"
      "               stamp of that frame (navemu's send time on vcan, without this reader).\n"
      "  gap       monotonic time between consecutive arrivals (ideal: 1 / rate)\n"
      "  lateness  arrival - (epoch time as Unix time + the profile's output latency), i.e.\n"
      "            how late against navemu's ideal deadline on the system clock\n"
      "  missing   epochs absent between the first and the last one seen\n"
      "Meanwhile a floor thread sleeps to absolute deadlines (clock_nanosleep TIMER_ABSTIME,\n"
      "CLOCK_MONOTONIC) at the highest rate measured and records its wake-up lateness: what the\n"
      "OS allows any writer here. The last two columns are each stream's p99 lateness over\n"
      "the floor's p99: as measured, and above the stream's own minimum (-min/fl.). navemu's\n"
      "lateness holds a fixed offset (GPS time is tied to the system clock once, at its start:\n"
      "run it with start 'now', the default), and the reader rows this reader's own wake-up;\n"
      "p99 - min leaves the offset out. Rates and latencies come from the profiles navemu runs\n"
      "with (--gnss-profile, --imu-profile: a name in configs/ or a YAML path). Nothing passes\n"
      "or fails on timing: the exit code is 0 when every stream gave at least two epochs, 1\n"
      "when one did not, 2 on bad options or a port that cannot be opened.\n"
      "Examples:\n"
      "  navemu run & navemu-jitter --pty /tmp/navemu-gnss --seconds 30\n"
      "  navemu-jitter --pty /tmp/g --gnss-profile ublox-nmea-5hz --can vcan0 --load\n"
      "  tools/jitter-probe runs navemu and this probe for both streams (inside user-mode Linux\n"
      "  when this kernel has no vcan0).");
  app.add_option("--pty", pty.path, "The pty (or device) navemu writes NMEA to");
  app.add_option("--can", can.iface,
                 "The SocketCAN interface navemu sends the IMU's highres frames on");
  app.add_option("--seconds", seconds, "Seconds to measure (default 30)")
      ->check(CLI::PositiveNumber);
  app.add_option("--gnss-profile", gnss_profile,
                 "GNSS profile navemu runs (name or YAML path): rate and output latency "
                 "(default garmin-18x-5hz)");
  app.add_option("--imu-profile", imu_profile,
                 "IMU profile navemu runs (name or YAML path): output rate and latency "
                 "(default paper_phidget)");
  app.add_option("--sentence", pty.sentence,
                 "Sentence type that starts an epoch, without talker (default RMC)");
  app.add_option("--can-base-id", base_id,
                 "Identifier of HR_TIME, imu.can.highres.base_id (default 0x500)");
  app.add_flag("--can-extended", can.layout.extended,
               "29-bit identifiers (imu.can.highres.extended)");
  app.add_flag("--load", load, "Spin a busy thread pinned to the last CPU meanwhile");
  app.add_option("--markdown", markdown_path, "Also write the table as markdown to this file");
  app.add_option(
      "--csv", csv_path,
      "Also write every arrival: stream,epoch_ns,mono_ns,real_ns,kernel_real_ns,lateness_ms");
  CLI11_PARSE(app, argc, argv);
  can.layout.base_id = base_id;
  const bool use_pty = !pty.path.empty(), use_can = !can.iface.empty();
  if (!use_pty && !use_can) {
    fmt::print(stderr, "navemu-jitter: give --pty PATH, --can IFACE or both (try --help)\n");
    return 2;
  }

  double pty_rate = 0, can_rate = 0;
  try {
    if (use_pty) {
      const navemu::GnssProfile g = navemu::load_gnss_profile(gnss_profile);
      pty_rate = g.rate_hz;
      pty.latency_ns = std::llround(g.output_latency_s * 1e9);
      pty.period_ns = std::llround(1e9 / g.rate_hz);
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "navemu-jitter: --gnss-profile {}: {}\n", gnss_profile, e.what());
    return 2;
  }
  try {
    if (use_can) {
      const navemu::ImuProfile p = navemu::load_imu_profile(imu_profile);
      can_rate = p.params.output_rate_hz;
      can.latency_ns = std::llround(p.params.latency_s * 1e9);
      can.period_ns = std::llround(1e9 / can_rate);
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "navemu-jitter: --imu-profile {}: {}\n", imu_profile, e.what());
    return 2;
  }
  try {
    if (use_can) can.start();
    if (use_pty) pty.start();
  } catch (const std::exception& e) {
    fmt::print(stderr, "navemu-jitter: {}\n", e.what());
    return 2;
  }

  const double floor_rate = std::max(pty_rate, can_rate);
  const auto floor_period_ns = static_cast<std::int64_t>(std::llround(1e9 / floor_rate));
  const std::int64_t end_mono = now_ns(CLOCK_MONOTONIC) + std::llround(seconds * 1e9);
  const auto expected = [&](double rate) { return static_cast<std::size_t>(seconds * rate) + 16; };
  std::vector<double> floor_late_ms;
  floor_late_ms.reserve(expected(floor_rate));
  pty.arrivals.reserve(expected(pty_rate));
  can.arrivals.reserve(expected(can_rate));
  std::thread timer(floor_timer, floor_period_ns, end_mono, std::ref(floor_late_ms));
  std::thread loader;
  const long ncpu = ::sysconf(_SC_NPROCESSORS_ONLN);
  if (load) loader = std::thread(spin, static_cast<int>(std::max(0L, ncpu - 1)));

  // Until the end, or until every port has closed (navemu stopped).
  for (;;) {
    const std::int64_t left = end_mono - now_ns(CLOCK_MONOTONIC);
    if (left <= 0 || (!pty.open && !can.open)) break;
    std::array<pollfd, 2> p{};
    nfds_t n = 0;
    if (pty.open) p[n++] = {pty.fd, POLLIN, 0};
    if (can.open) p[n++] = {can.sock, POLLIN, 0};
    if (::poll(p.data(), n, static_cast<int>(left / 1'000'000 + 1)) <= 0) continue;
    for (nfds_t i = 0; i < n; ++i) {
      if (p[i].revents == 0) continue;
      const bool is_pty = pty.open && p[i].fd == pty.fd;
      const bool alive = is_pty ? pty.on_readable() : can.on_readable();
      if (alive) continue;
      fmt::print(stderr, "navemu-jitter: {} closed after {:.1f} s\n", is_pty ? pty.path : can.iface,
                 seconds - static_cast<double>(end_mono - now_ns(CLOCK_MONOTONIC)) * 1e-9);
      (is_pty ? pty.open : can.open) = false;
    }
  }
  g_done.store(true);
  timer.join();
  if (loader.joinable()) loader.join();
  if (pty.fd >= 0) ::close(pty.fd);
  if (can.sock >= 0) ::close(can.sock);

  std::vector<Row> rows;
  if (use_pty)
    rows.push_back(stream_row(fmt::format("pty {} ({:g} Hz)", pty.sentence, pty_rate), pty.arrivals,
                              pty.period_ns, false));
  if (use_can) {
    rows.push_back(stream_row(fmt::format("can {} highres ({:g} Hz)", can.iface, can_rate),
                              can.arrivals, can.period_ns, false));
    const bool stamped = std::all_of(can.arrivals.begin(), can.arrivals.end(),
                                     [](const Arrival& a) { return a.kernel_real_ns != 0; });
    if (stamped)
      rows.push_back(stream_row(fmt::format("can {} kernel rx stamp", can.iface), can.arrivals,
                                can.period_ns, true));
  }
  {
    // The timer's "gap" is its period plus the difference of consecutive lateness values.
    std::vector<double> gaps_ms;
    for (std::size_t i = 1; i < floor_late_ms.size(); ++i)
      gaps_ms.push_back(static_cast<double>(floor_period_ns) * 1e-6 + floor_late_ms[i] -
                        floor_late_ms[i - 1]);
    Row f;
    f.name = fmt::format("floor: clock_nanosleep ({:g} Hz)", floor_rate);
    f.gap = stats(gaps_ms);
    f.late = stats(floor_late_ms);
    f.is_floor = true;
    rows.push_back(f);
  }

  std::string caption = fmt::format("{:.0f} s, load {}, {} CPU{}", seconds, load ? "on" : "off",
                                    ncpu, ncpu == 1 ? "" : "s");
  if (use_pty)
    caption += fmt::format("; pty: {} ({}, latency {:g} ms)", pty.path, gnss_profile,
                           static_cast<double>(pty.latency_ns) * 1e-6);
  if (use_can)
    caption += fmt::format("; can: {} ({}, latency {:g} ms)", can.iface, imu_profile,
                           static_cast<double>(can.latency_ns) * 1e-6);
  fmt::print("navemu-jitter: {}\n", caption);
  print_table(rows);
  if (use_pty && pty.bad) fmt::print("pty: {} sentences failed their checksum\n", pty.bad);
  if (use_can && (can.bad || can.socket_drops))
    fmt::print(
        "can: {} samples incomplete or failing their CRC, {} frames dropped by this reader's "
        "socket\n",
        can.bad, can.socket_drops);

  if (!markdown_path.empty()) {
    std::ofstream md(markdown_path);
    md << markdown_table(caption +
                             ". Lateness = arrival - (epoch time + profile latency); the "
                             "floor is a bare clock_nanosleep timer in the same run; p99 - min "
                             "leaves out a stream's fixed offset.",
                         rows);
    if (!md) {
      fmt::print(stderr, "navemu-jitter: cannot write {}\n", markdown_path);
      return 2;
    }
  }
  if (!csv_path.empty()) {
    std::ofstream csv(csv_path);
    csv << "stream,epoch_ns,mono_ns,real_ns,kernel_real_ns,lateness_ms\n";
    const auto dump = [&](const char* stream, const std::vector<Arrival>& arr) {
      for (const Arrival& a : arr)
        csv << fmt::format("{},{},{},{},{},{:.4f}\n", stream, a.epoch_ns, a.mono_ns, a.real_ns,
                           a.kernel_real_ns, static_cast<double>(a.real_ns - a.due_unix_ns) * 1e-6);
    };
    dump("pty", pty.arrivals);
    dump("can", can.arrivals);
    if (!csv) {
      fmt::print(stderr, "navemu-jitter: cannot write {}\n", csv_path);
      return 2;
    }
  }
  const bool enough =
      (!use_pty || pty.arrivals.size() >= 2) && (!use_can || can.arrivals.size() >= 2);
  if (!enough)
    fmt::print(stderr, "navemu-jitter: fewer than two epochs on a stream: is navemu running?\n");
  return enough ? 0 : 1;
}
