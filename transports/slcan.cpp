// slcan port: the Lawicel ASCII protocol of the CAN232/CANUSB adapters (LAWICEL CANUSB manual,
// "ASCII command set"), with the CAN FD frame letters d/D/b/B of the CANable 2 firmware
// (normaldotcom/canable2-fw, src/slcan.c), as python-can's slcan interface reads them.

#include <array>
#include <cctype>
#include <string_view>

#include "transports/can_port.hpp"
#include "transports/can_util.hpp"

namespace navemu::transport {
namespace {

constexpr char kHex[] = "0123456789ABCDEF";
// The longest command: an extended CAN FD frame with 64 bytes, "B" + 8 + 1 + 128 characters.
constexpr std::size_t kMaxLine = 138;
// The longest frame line we send, with its CR.
constexpr std::size_t kMaxFrameLine = kMaxLine + 1;

bool all_hex(std::string_view s) {
  for (const char c : s)
    if (std::isxdigit(static_cast<unsigned char>(c)) == 0) return false;
  return !s.empty();
}

std::uint32_t hex_value(std::string_view s) {
  std::uint32_t v = 0;
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(std::toupper(static_cast<unsigned char>(c)));
    v = v * 16 + static_cast<std::uint32_t>(u <= '9' ? u - '0' : u - 'A' + 10);
  }
  return v;
}

// Whether `line` is a well-formed frame command: t/r iiil, T/R iiiiiiiil, then for t/T/d/D/b/B
// two hex digits per data byte (CANUSB manual "t", "T", "r", "R"; canable2-fw slcan_parse_str).
bool valid_frame_command(std::string_view line) {
  const char cmd = line[0];
  const bool extended = std::isupper(static_cast<unsigned char>(cmd)) != 0;
  const bool fd = cmd == 'd' || cmd == 'D' || cmd == 'b' || cmd == 'B';
  const bool remote = cmd == 'r' || cmd == 'R';
  const std::size_t id_digits = extended ? 8 : 3;
  if (line.size() < 1 + id_digits + 1 || !all_hex(line.substr(1, id_digits + 1))) return false;
  if (hex_value(line.substr(1, id_digits)) > (extended ? 0x1FFFFFFFu : 0x7FFu)) return false;
  const auto dlc = static_cast<std::uint8_t>(hex_value(line.substr(1 + id_digits, 1)));
  if (!fd && dlc > 8) return false;
  const std::string_view data = line.substr(2 + id_digits);
  if (remote) return data.empty();
  return data.size() == 2 * can_length_from_dlc(dlc) && (data.empty() || all_hex(data));
}

class SlcanPort final : public FramePort {
 public:
  SlcanPort(std::unique_ptr<BytePort> port, const SlcanOptions& opt)
      : port_(std::move(port)), open_(opt.auto_open) {
    line_.reserve(kMaxLine);
    out_.reserve(kMaxFrameLine);
  }

  bool write(const CanFrameView& frame, std::int64_t) override {
    if (!valid_can_frame(frame)) {
      counters_.frames_failed++;
      return false;
    }
    if (!open_) {
      counters_.frames_held++;  // an adapter passes no frames while its channel is closed
      return false;
    }
    encode_slcan(frame, out_);
    if (!port_->write(out_)) {
      counters_.frames_dropped++;
      return false;
    }
    counters_.frames_written++;
    return true;
  }

  // Reads the client's commands (in any pieces) and answers each complete one.
  void service() override {
    port_->service();
    std::array<std::uint8_t, 512> buf;
    for (int round = 0; round < 16; ++round) {
      const std::size_t n = port_->read(buf);
      if (n == 0) break;
      for (std::size_t i = 0; i < n; ++i) feed(static_cast<char>(buf[i]));
    }
  }

  std::string describe() const override { return "slcan on " + port_->describe(); }
  bool fd_capable() const override { return true; }

 private:
  void feed(char c) {
    if (c == '\r') {
      if (!overflow_ && !line_.empty()) execute(line_);
      line_.clear();
      overflow_ = false;
    } else if (c == '\n' && line_.empty()) {
      // The LF of a CR LF line end: ignored.
    } else if (overflow_) {
      // The rest of an over-long line: already answered.
    } else if (line_.size() == kMaxLine) {
      counters_.commands++;
      fail();
      line_.clear();
      overflow_ = true;
    } else {
      line_.push_back(c);
    }
  }

  // One command line without its CR (CANUSB manual, "ASCII command set"). An empty line is
  // ignored: clients send a few CRs to clear an adapter's buffer of half-sent commands.
  void execute(std::string_view line) {
    counters_.commands++;
    const char cmd = line[0];
    const std::string_view arg = line.substr(1);
    switch (cmd) {
      case 'O':
      case 'L':
        if (!arg.empty() || open_) return fail();
        open_ = true;
        return reply("\r");
      case 'C':
        if (!arg.empty()) return fail();
        open_ = false;
        return reply("\r");
      case 'S':  // S0..S8: 10 kbit/s .. 1 Mbit/s
        if (open_ || arg.size() != 1 || arg[0] < '0' || arg[0] > '8') return fail();
        return reply("\r");
      case 's':  // sXXYY: SJA1000 BTR0, BTR1
        if (open_ || arg.size() != 4 || !all_hex(arg)) return fail();
        return reply("\r");
      case 'V':
        return arg.empty() ? reply("V1013\r") : fail();
      case 'v':
        return arg.empty() ? reply("vSTM32\r") : fail();
      case 'N':
        return arg.empty() ? reply("NNAVE\r") : fail();
      case 'F':
        return arg.empty() ? reply("F00\r") : fail();
      case 'Z':
        if (arg != "0" && arg != "1") return fail();
        return reply("\r");
      case 't':
      case 'r':
      case 'd':
      case 'b':
      case 'T':
      case 'R':
      case 'D':
      case 'B':
        // Transmit requests are only accepted while the channel is open (CANUSB manual).
        if (!open_ || !valid_frame_command(line)) return fail();
        return reply(std::isupper(static_cast<unsigned char>(cmd)) != 0 ? "Z\r" : "z\r");
      case 'M':
      case 'm':
      case 'X':
      case 'W':
      case 'Q':
        return reply("\r");
      default:
        return fail();
    }
  }

  void reply(std::string_view text) { port_->write(text); }
  void fail() {
    counters_.errors++;
    reply("\a");
  }

  std::unique_ptr<BytePort> port_;
  bool open_;
  std::string line_;  // the command being received, without CR
  bool overflow_ = false;
  std::string out_;  // the frame line being sent
};

}  // namespace

std::unique_ptr<FramePort> open_slcan(std::unique_ptr<BytePort> port, const SlcanOptions& opt) {
  return std::make_unique<SlcanPort>(std::move(port), opt);
}

// tIIIL / TIIIIIIIIL (classic), dIIIL / DIIIIIIIIL (FD), bIIIL / BIIIIIIIIL (FD with bit-rate
// switch), then two upper-case hex digits per byte and CR (CANUSB manual "t" and "T";
// canable2-fw slcan_parse_frame for d/D/b/B, whose DLC digit is the FD DLC code 0..F).
void encode_slcan(const CanFrameView& frame, std::string& out) {
  out.clear();
  char letter = frame.fd ? (frame.brs ? 'b' : 'd') : 't';
  if (frame.extended) letter = static_cast<char>(std::toupper(static_cast<unsigned char>(letter)));
  out.push_back(letter);
  for (int shift = frame.extended ? 28 : 8; shift >= 0; shift -= 4)
    out.push_back(kHex[(frame.id >> shift) & 0xFu]);
  out.push_back(kHex[can_dlc_from_length(frame.data.size())]);
  for (const std::uint8_t b : frame.data) {
    out.push_back(kHex[b >> 4]);
    out.push_back(kHex[b & 0xFu]);
  }
  out.push_back('\r');
}

}  // namespace navemu::transport
