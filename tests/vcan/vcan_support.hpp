#pragma once
// Helpers for the tests on a (virtual) CAN bus: skipping without kernel CAN, navemu's CAN
// counts from its summary line, and can-utils' candump as the bus's reader, with its own losses
// told apart from navemu's.
//
// Two parties can lose a frame. navemu counts every frame of every sample as written (handed to
// the kernel), dropped (ENOBUFS: the interface queue is full) or failed (its summary line). The
// reader loses frames when it falls behind: its socket's receive queue fills and the kernel
// drops what comes next, counting them for that socket (SO_RXQ_OVFL, socket(7)); candump -d
// prints that count. CandumpRecording starts candump with a queue sized for a stall, and ends
// the recording with marker frames so that the count covers every frame sent before the end:
// then frames logged + frames the reader dropped = frames navemu wrote, exactly.

#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "tests/can_capture.hpp"
#include "tests/clients/client_support.hpp"
#include "transports/can_port.hpp"

namespace navemu::test::clients {

#define NAVEMU_REQUIRE_KERNEL_CAN()                                                       \
  do {                                                                                    \
    if (!transport::socketcan_available())                                                \
      GTEST_SKIP() << "no kernel CAN here: run through tools/run-in-uml (ctest -L vcan)"; \
  } while (0)

#define NAVEMU_REQUIRE_VCAN0()                                                                  \
  do {                                                                                          \
    NAVEMU_REQUIRE_KERNEL_CAN();                                                                \
    if (::if_nametoindex("vcan0") == 0) GTEST_SKIP() << "no vcan0 (tools/run-in-uml makes it)"; \
  } while (0)

// The summary's IMU and CAN counts: "... N IMU samples (K skipped), ..., W CAN frames (D
// dropped, F failed, B bus errors)" (emulator/run_command.cpp).
struct CanSummary {
  long samples = 0, written = 0, dropped = 0, failed = 0, bus_errors = 0;
};
inline std::optional<CanSummary> can_summary(const std::string& err) {
  static const std::regex re(
      R"((\d+) IMU samples .*, (\d+) CAN frames \((\d+) dropped, (\d+) failed, (\d+) bus errors\))");
  std::smatch m;
  if (!std::regex_search(err, m, re)) return std::nullopt;
  return CanSummary{std::stol(m[1]), std::stol(m[2]), std::stol(m[3]), std::stol(m[4]), std::stol(m[5])};
}

// The receive queue a reader needs to sit out a stall of `stall_s` at `frames_per_s` without a
// loss: every queued frame is charged its socket buffer's truesize, 768 bytes inside
// user-mode Linux 6.1 for classic and CAN FD frames alike (measured there: SO_MEMINFO's
// rmem_alloc after queueing ten frames of each kind; the kernel's default queue,
// net.core.rmem_default = 212992 bytes, so holds 278 frames). Never less than that default.
inline constexpr long kCanFrameTruesizeBytes = 768;
inline constexpr long kDefaultReceiveQueueBytes = 212992;
inline long receive_queue_bytes(double frames_per_s, double stall_s) {
  return std::max(kDefaultReceiveQueueBytes,
                  static_cast<long>(frames_per_s * stall_s * static_cast<double>(kCanFrameTruesizeBytes)));
}

// The reader stall the recordings are sized for. The failure that asked for it: candump under
// user-mode Linux lost 423 frames at 1000 frames/s behind the default queue of 278, a stall of
// about 0.7 s; 2 s covers about three times that.
inline constexpr double kReaderStallS = 2.0;

// What a recording holds once ended.
struct CandumpResult {
  std::vector<LoggedFrame> frames;  // everything logged but the markers, with the holes marked
  std::uint64_t dropped = 0;        // of those frames, how many candump's socket dropped
  bool ended = false;               // the last end marker arrived: `dropped` is complete
  std::string problem;              // why not
};

// can-utils' candump recording one interface into DIR/candump.log: -L (log format), -d (the
// socket's drops, as "DROPCOUNT" lines before the first frame after them), -r (the receive
// queue; the kernel doubles the size asked for, socket(7) SO_RCVBUF, and candump sets it with
// SO_RCVBUFFORCE, so past net.core.rmem_max when root, as inside user-mode Linux; otherwise it
// falls back to SO_RCVBUF, capped by rmem_max, and says so on stderr) and -D (it stays when
// the interface goes down). Checked in can-utils 2020.11's candump.c and inside user-mode Linux:
// a reader stopped while 2500 frames came logged 2000 of them with -r 768000 (1536000 bytes /
// 768) and reported the other 500 in one DROPCOUNT line.
//
// Marker frames, sent from a socket of the test, frame the recording (identifier 0x7FF, data
// "S" or "E" and a count; not a frame navemu sends): a start marker in the log shows candump is
// receiving. At the end, end markers follow until the last one sent is in the log, so every
// frame sent before it is either logged or counted in a DROPCOUNT line; a marker the reader
// dropped itself is taken off the count. (The start markers go into an empty queue.)
class CandumpRecording {
 public:
  static constexpr std::uint32_t kMarkerId = 0x7FF;

  // The receive queue holds `stall_s` of frames at `frames_per_s` (0: the kernel's default);
  // `error_frames`: error frames too (an accept-all filter and the error mask on the interface,
  // "IFACE,0:0,#FFFFFFFF": candump refuses -e with -L; logged with CAN_ERR_FLAG in the
  // identifier).
  CandumpRecording(const TempDir& dir, std::string iface, double frames_per_s, double stall_s = kReaderStallS,
                   bool error_frames = false)
      : iface_(std::move(iface)), log_(dir / "candump.log"), err_(dir / "candump.stderr") {
    const std::string candump = find_program("candump");
    const long queue = receive_queue_bytes(frames_per_s, stall_s);
    if (candump.empty()) return;
    dump_.start({candump, "-L", "-d", "-D", "-r", std::to_string(queue / 2), iface_ + (error_frames ? ",0:0,#FFFFFFFF" : "")},
                log_, err_);
    sock_ = ::socket(AF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
    if (sock_ >= 0) ::setsockopt(sock_, SOL_CAN_RAW, CAN_RAW_FILTER, nullptr, 0);  // sends only
    sockaddr_can addr{};
    addr.can_family = AF_CAN;
    addr.can_ifindex = static_cast<int>(::if_nametoindex(iface_.c_str()));
    if (sock_ < 0 || ::bind(sock_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) return;
    const double give_up = mono_s() + 10.0;
    while (!receiving_ && dump_.running() && mono_s() < give_up) receiving_ = send_and_wait('S', 0.2);
  }
  ~CandumpRecording() {
    if (sock_ >= 0) ::close(sock_);
  }
  CandumpRecording(const CandumpRecording&) = delete;
  CandumpRecording& operator=(const CandumpRecording&) = delete;

  // candump has logged a start marker: it receives everything sent from now on.
  bool receiving() const { return receiving_; }
  std::string diagnostics() const {
    return "\n--- candump stderr (" + err_.string() + ") ---\n" + tail(slurp(err_)) + "\n---";
  }

  // Stops candump (SIGSTOP) for `seconds`, as a reader the scheduler or the disk holds up.
  void stall(double seconds) {
    ::kill(dump_.pid(), SIGSTOP);
    sleep_s(seconds);
    ::kill(dump_.pid(), SIGCONT);
  }

  // Sends end markers until the last one sent is in the log (one a second, for at most 10 s),
  // stops candump and reads its log.
  CandumpResult finish() {
    CandumpResult r;
    bool ended = false;
    const double give_up = mono_s() + 10.0;
    while (!ended && dump_.running() && mono_s() < give_up) ended = send_and_wait('E', 1.0);
    dump_.signal(SIGINT);
    if (!dump_.wait_exit(5.0)) r.problem = "candump did not stop on SIGINT. ";
    // A marker's drops go to the next frame kept or, after the last one, to its end.
    std::uint64_t carried = 0, end_markers = 0;
    for (LoggedFrame& f : read_candump_log(log_)) {
      if (is_marker(f)) {
        carried += f.dropped_before + f.dropped_after;
        if (f.data[0] == 'E') ++end_markers;
        continue;
      }
      f.dropped_before += std::exchange(carried, 0);
      r.frames.push_back(std::move(f));
    }
    if (!r.frames.empty()) r.frames.back().dropped_after += std::exchange(carried, 0);
    const std::uint64_t all = reader_dropped(r.frames) + carried;
    const std::uint64_t markers_dropped = end_sent_ - std::min(end_sent_, end_markers);
    r.dropped = all - std::min(all, markers_dropped);
    r.ended = ended && r.problem.empty();
    if (!ended)
      r.problem += fmt::format("the last of {} end markers never reached candump's log{}", end_sent_,
                               write_error_.empty() ? "" : " (last write error: " + write_error_ + ")");
    return r;
  }

 private:
  static bool is_marker(const LoggedFrame& f) {
    return !f.extended && !f.fd && f.id == kMarkerId && f.data.size() == 2 &&
           (f.data[0] == 'S' || f.data[0] == 'E');
  }

  // Sends the next marker of `kind` and waits up to `timeout_s` for it in the log.
  bool send_and_wait(char kind, double timeout_s) {
    const auto n = static_cast<std::uint8_t>(sent_ + 1);
    can_frame f{};
    f.can_id = kMarkerId;
    f.len = 2;
    f.data[0] = static_cast<std::uint8_t>(kind);
    f.data[1] = n;
    // A write fails once after the interface went down and up (the socket's pending ENETDOWN),
    // and while a queueing discipline in front of the interface is full (ENOBUFS; the CanFaults
    // token bucket drains its 720 bytes in 0.15 s): the caller tries again a little later.
    if (::write(sock_, &f, sizeof f) != static_cast<ssize_t>(sizeof f)) {
      write_error_ = std::strerror(errno);
      sleep_s(0.05);
      return false;
    }
    ++sent_;
    if (kind == 'E') ++end_sent_;
    const std::string line = fmt::format(" {} {:03X}#{:02X}{:02X}\n", iface_, kMarkerId, f.data[0], n);
    return wait_until([&] { return log_end().find(line) != std::string::npos; }, timeout_s, 0.01);
  }

  // The last 4 kB of the log: where a marker lands when nothing else is sent.
  std::string log_end() const {
    std::ifstream in(log_, std::ios::binary | std::ios::ate);
    const std::streamoff size = in.tellg();
    if (size <= 0) return {};
    const std::streamoff from = std::max<std::streamoff>(0, size - 4096);
    std::string s(static_cast<std::size_t>(size - from), '\0');
    in.seekg(from);
    in.read(s.data(), static_cast<std::streamsize>(s.size()));
    return s;
  }

  std::string iface_;
  fs::path log_, err_;
  Child dump_;
  int sock_ = -1;
  unsigned sent_ = 0;
  std::uint64_t end_sent_ = 0;
  std::string write_error_;
  bool receiving_ = false;
};

}  // namespace navemu::test::clients
