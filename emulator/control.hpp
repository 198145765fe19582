#pragma once
// Live control of a running `navemu run` (issue "impairments"): JSON lines on a TCP port that
// binds to loopback by default (`control:` in the configuration; `navemu ctl` sends them). One
// JSON object per line, one reply line each:
//   {"cmd": "event", "type": "jamming", "duration_s": 10, "j_over_s_db": 45, ...}
//       an event with the keys of `events:` (configs/default.yaml; GNSS, IMU and truth), its
//       start_s counted from "now" (a GNSS event's next epoch, an IMU fault's next sample, the
//       later of the two for a truth fault; 0 when absent), or its start at GPS time `at`;
//       reply {"ok": true, "from": ISO UTC, "gps": "WEEK:TOW"}
//   {"cmd": "clear"}
//       ends every event, those of the configuration too; reply {"ok": true}
// emulator/control_channel.hpp applies them to the run.
// A malformed or unknown command is refused: {"ok": false, "error": "<why>"}. Replies go to
// every client connected to the port. At most kMaxControlLinesPerTick lines are taken per
// service tick, the rest at the next ones, so a flood of commands cannot hold the loop; a line
// longer than kMaxControlLine bytes is refused whole.

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "emulator/run_config.hpp"
#include "models/measurement.hpp"
#include "transports/byte_port.hpp"

namespace navemu {

inline constexpr std::size_t kMaxControlLine = 4096;
inline constexpr int kMaxControlLinesPerTick = 16;

struct ControlEvent {  // one event in one of the lists, start_s counted from now
  GnssEvents events;
  std::vector<ImuFault> imu;
  std::vector<TruthFault> truth;
};
struct ControlClear {};
using ControlCommand = std::variant<ControlEvent, ControlClear>;

// One line (without its newline) as a command, or the reason it is refused.
std::variant<ControlCommand, std::string> parse_control_line(std::string_view line);

// `text` as a JSON string literal, quotes included.
std::string json_string(std::string_view text);

// The line framing of a control port: bytes in, at most kMaxControlLinesPerTick whole lines out
// per call, a reply line written back for each.
class ControlPort {
 public:
  explicit ControlPort(std::unique_ptr<transport::BytePort> port);
  // Reads what arrived and answers the complete lines: `reply(line)` gives each one's reply
  // (without newline).
  template <typename Reply>
  void service(Reply&& reply) {
    port_->service();
    take_input();
    std::string_view line;
    for (int n = 0; n < kMaxControlLinesPerTick && next_line(line); ++n) {
      if (line.empty() && !too_long_) {  // blank lines are no commands
        consume_line();
        continue;
      }
      const std::string r = too_long_ ? refuse_too_long() : reply(line);
      port_->write(r + "\n");
      consume_line();
    }
  }
  std::string describe() const { return port_->describe(); }
  const transport::BytePort& port() const { return *port_; }

 private:
  void take_input();
  bool next_line(std::string_view& line);
  void consume_line();
  std::string refuse_too_long();
  std::unique_ptr<transport::BytePort> port_;
  std::string pending_;        // received, not yet answered
  std::size_t line_end_ = 0;   // of the line next_line() gave
  bool too_long_ = false;      // that line was cut at kMaxControlLine
  bool skipping_ = false;      // dropping the rest of an over-long line
};

}  // namespace navemu
