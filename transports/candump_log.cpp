// candump log port: the log format of can-utils `candump -L` (candump.c, lib.c
// snprintf_canframe): "(seconds.microseconds) interface frame", where the frame is
// III#DD.. (standard), IIIIIIII#DD.. (extended) or ID##FDD.. (CAN FD, F = flags nibble with
// CANFD_BRS 1 and CANFD_ESI 2 of linux/can.h). Written through open_log_file's buffer.

#include <fmt/compile.h>
#include <fmt/format.h>

#include <iterator>

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
  auto it = std::back_inserter(out);
  const std::int64_t us = unix_time_ns >= 0 ? unix_time_ns / 1000 : (unix_time_ns - 999) / 1000;
  std::int64_t sec = us / 1000000;
  std::int64_t usec = us % 1000000;
  if (usec < 0) {
    usec += 1000000;
    sec -= 1;
  }
  it = fmt::format_to(it, FMT_COMPILE("({:010d}.{:06d}) "), sec, usec);
  out.append(interface_name);
  out.push_back(' ');
  if (frame.extended)
    it = fmt::format_to(it, FMT_COMPILE("{:08X}"), frame.id);
  else
    it = fmt::format_to(it, FMT_COMPILE("{:03X}"), frame.id);
  if (frame.fd)
    it = fmt::format_to(it, FMT_COMPILE("##{:X}"), frame.brs ? 1 : 0);
  else
    *it++ = '#';
  static constexpr char kHex[] = "0123456789ABCDEF";  // the payload, the bulk of the line
  for (const std::uint8_t b : frame.data) {
    out.push_back(kHex[b >> 4]);
    out.push_back(kHex[b & 0x0F]);
  }
  out.push_back('\n');
}

}  // namespace navemu::transport
