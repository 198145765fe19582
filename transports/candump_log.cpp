// candump log port: the log format of can-utils `candump -L` (candump.c, lib.c
// snprintf_canframe): "(seconds.microseconds) interface frame", where the frame is
// III#DD.. (standard), IIIIIIII#DD.. (extended) or ID##FDD.. (CAN FD, F = flags nibble with
// CANFD_BRS 1 and CANFD_ESI 2 of linux/can.h). Written through open_log_file's buffer.

#include <fmt/compile.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "transports/can_port.hpp"
#include "transports/can_util.hpp"

namespace navemu::transport {
namespace {

// "(1700000000.123456) " + interface + " " + "12345678##1" + 128 hex digits + "\n"
constexpr std::size_t kLineReserve = 192;

class CandumpLog final : public FramePort {
 public:
  explicit CandumpLog(const CandumpLogOptions& opt)
      : file_(open_log_file(opt.path)), path_(opt.path), interface_(opt.interface_name) {
    line_.reserve(kLineReserve + interface_.size());
  }

  bool write(const CanFrameView& frame, std::int64_t unix_time_ns) override {
    if (!valid_can_frame(frame)) {
      counters_.frames_failed++;
      return false;
    }
    format_candump_line(frame, unix_time_ns, interface_, line_);
    if (!file_->write(line_)) {  // the file failed (disk full); reported once by the file
      counters_.frames_dropped++;
      return false;
    }
    counters_.frames_written++;
    return true;
  }

  void service() override { file_->service(); }
  std::string describe() const override { return "candump log " + path_; }
  bool fd_capable() const override { return true; }
  bool carries_error_frames() const override { return true; }

 private:
  std::unique_ptr<BytePort> file_;
  std::string path_;
  std::string interface_;
  std::string line_;
};

}  // namespace

std::unique_ptr<FramePort> open_candump_log(const CandumpLogOptions& opt) {
  return std::make_unique<CandumpLog>(opt);
}

// candump -L prints the time stamp as "(%010lu.%06lu)" of the frame's struct timeval.
void format_candump_line(const CanFrameView& frame, std::int64_t unix_time_ns,
                         std::string_view interface_name, std::string& out) {
  out.clear();
  const std::int64_t us = unix_time_ns >= 0 ? unix_time_ns / 1000 : (unix_time_ns - 999) / 1000;
  std::int64_t sec = us / 1000000;
  std::int64_t usec = us % 1000000;
  if (usec < 0) {
    usec += 1000000;
    sec -= 1;
  }
  // Formatted into local buffers and appended whole: one CAN log line per frame, offline
  // hundreds of thousands of them.
  std::array<char, 32> stamp{};
  out.append(stamp.data(), fmt::format_to(stamp.data(), FMT_COMPILE("({:010d}.{:06d}) "), sec, usec));
  out.append(interface_name);
  // " IIIIIIII##F" and the payload, 64 bytes at most (CAN FD), as hex.
  std::array<char, 12 + 2 * 64 + 1> body{};
  char* p = body.data();
  *p++ = ' ';
  // An error frame: its can_id with CAN_ERR_FLAG (0x20000000), 8 digits (lib.c sprint_canframe).
  p = frame.error      ? fmt::format_to(p, FMT_COMPILE("{:08X}"), frame.id | 0x20000000u)
      : frame.extended ? fmt::format_to(p, FMT_COMPILE("{:08X}"), frame.id)
                       : fmt::format_to(p, FMT_COMPILE("{:03X}"), frame.id);
  *p++ = '#';
  if (frame.fd) {
    *p++ = '#';
    *p++ = frame.brs ? '1' : '0';
  }
  static constexpr char kHex[] = "0123456789ABCDEF";
  for (const std::uint8_t b : frame.data.first(std::min<std::size_t>(frame.data.size(), 64))) {
    *p++ = kHex[b >> 4];
    *p++ = kHex[b & 0x0F];
  }
  *p++ = '\n';
  out.append(body.data(), p);
}

}  // namespace navemu::transport
