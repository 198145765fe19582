#include "emulator/control.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <array>

#include "core/errors.hpp"
#include "emulator/run_config.hpp"
#include "emulator/yaml_reader.hpp"

namespace navemu {

std::variant<ControlCommand, std::string> parse_control_line(std::string_view line) {
  YAML::Node n;
  try {
    n = YAML::Load(std::string(line));  // JSON is YAML's flow style
  } catch (const YAML::Exception& e) {
    return fmt::format("not a JSON object: {}", e.msg);
  }
  if (!n.IsMap()) return std::string(R"(a command is one JSON object per line, e.g. {"cmd": "clear"})");
  try {
    YamlMap m("control", n, "command");
    const std::optional<std::string> cmd = m.text("cmd");
    if (!cmd) m.fail("cmd", "missing: event or clear");
    if (*cmd == "clear") {
      m.reject_unknown_keys();
      return ControlCommand{ControlClear{}};
    }
    if (*cmd != "event") m.fail("cmd", fmt::format("'{}' is not a command (event, clear)", *cmd));
    ControlEvent e;
    add_event(m, e.events, e.imu, e.truth);
    return ControlCommand{e};
  } catch (const InputError& e) {
    return std::string(e.what());
  }
}

std::string json_string(std::string_view text) {
  std::string out = "\"";
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20) {
      out += fmt::format("\\u{:04x}", c);
    } else {
      out += c < 0x80 ? ch : '?';  // the reply stays ASCII whatever the line held
    }
  }
  return out + "\"";
}

ControlPort::ControlPort(std::unique_ptr<transport::BytePort> port) : port_(std::move(port)) {}

void ControlPort::take_input() {
  std::array<std::uint8_t, 4096> buf;
  // Up to 16 lines' worth waits here; beyond, the bytes stay with the kernel (and the client).
  while (pending_.size() < 16 * kMaxControlLine) {
    const std::size_t n = port_->read(buf);
    if (n == 0) return;
    std::string_view in(reinterpret_cast<const char*>(buf.data()), n);
    if (skipping_) {  // the rest of an over-long line
      const std::size_t nl = in.find('\n');
      if (nl == std::string_view::npos) continue;
      in.remove_prefix(nl + 1);
      skipping_ = false;
    }
    pending_.append(in);
  }
}

bool ControlPort::next_line(std::string_view& line) {
  const std::size_t nl = pending_.find('\n');
  too_long_ = nl == std::string::npos ? pending_.size() > kMaxControlLine : nl > kMaxControlLine;
  if (nl == std::string::npos && !too_long_) return false;
  if (nl == std::string::npos) {  // no end in sight: refuse it now, drop the rest as it comes
    skipping_ = true;
    line_end_ = pending_.size();
  } else {
    line_end_ = nl + 1;
  }
  line = std::string_view(pending_).substr(0, std::min(line_end_, kMaxControlLine));
  if (!line.empty() && line.back() == '\n') line.remove_suffix(1);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return true;
}

void ControlPort::consume_line() { pending_.erase(0, line_end_); }

std::string ControlPort::refuse_too_long() {
  return fmt::format(R"({{"ok": false, "error": "line longer than {} bytes"}})", kMaxControlLine);
}

}  // namespace navemu
