// Live control (emulator/control.hpp): the command lines and their refusals, the JSON replies'
// escaping, and the line framing that bounds a flood of commands per service tick.

#include "emulator/control.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

namespace navemu {
namespace {

std::string refusal(std::string_view line) {
  const auto r = parse_control_line(line);
  const std::string* why = std::get_if<std::string>(&r);
  return why ? *why : "accepted";
}

TEST(Control, CommandsAndTheirRefusals) {
  const auto ev = parse_control_line(
      R"({"cmd": "event", "type": "jamming", "start_s": 2, "duration_s": 10, "j_over_s_db": 45, "kind": "cw"})");
  ASSERT_TRUE(std::holds_alternative<ControlCommand>(ev)) << refusal("");
  const auto& jam = std::get<ControlEvent>(std::get<ControlCommand>(ev)).events.jamming;
  ASSERT_EQ(jam.size(), 1u);
  EXPECT_EQ(jam[0].window.start_s, 2.0);
  EXPECT_EQ(jam[0].window.duration_s, 10.0);
  EXPECT_EQ(jam[0].j_over_s_db, 45.0);
  EXPECT_EQ(jam[0].kind, InterferenceKind::kCw);
  const auto out = parse_control_line(R"({"cmd": "event", "type": "outage", "duration_s": 3})");
  ASSERT_TRUE(std::holds_alternative<ControlCommand>(out));
  EXPECT_EQ(std::get<ControlEvent>(std::get<ControlCommand>(out)).events.outages.size(), 1u);
  const auto at = parse_control_line(R"({"cmd": "event", "type": "outage", "duration_s": 3, "at": "2394:475200"})");
  ASSERT_TRUE(std::holds_alternative<ControlCommand>(at));
  EXPECT_EQ(std::get<ControlEvent>(std::get<ControlCommand>(at)).events.outages.at(0).window.at, parse_time("2394:475200"));
  const auto imu = parse_control_line(
      R"({"cmd": "event", "type": "imu", "duration_s": 3, "fault": "bias", "sensor": "gyro", "bias_dps": 1})");
  ASSERT_TRUE(std::holds_alternative<ControlCommand>(imu)) << refusal("");
  EXPECT_EQ(std::get<ControlEvent>(std::get<ControlCommand>(imu)).imu.size(), 1u);
  const auto truth = parse_control_line(R"({"cmd": "event", "type": "truth", "duration_s": 3, "fault": "freeze"})");
  ASSERT_TRUE(std::holds_alternative<ControlCommand>(truth));
  EXPECT_EQ(std::get<ControlEvent>(std::get<ControlCommand>(truth)).truth.size(), 1u);
  const auto clear = parse_control_line(R"({"cmd": "clear"})");
  ASSERT_TRUE(std::holds_alternative<ControlCommand>(clear));
  EXPECT_TRUE(std::holds_alternative<ControlClear>(std::get<ControlCommand>(clear)));

  const std::pair<const char*, const char*> refused[] = {
      {R"({"cmd": "clear", "now": 1})", "command.now"},
      {R"({"type": "outage"})", "command.cmd: missing"},
      {R"({"cmd": "reboot"})", "'reboot' is not a command (event, clear)"},
      {R"({"cmd": "event", "type": "meaconing", "duration_s": 1})", "'meaconing' is not an event type"},
      {R"({"cmd": "event", "type": "spoofing", "duration_s": 1})", "command.offset_m: missing"},
      {R"({"cmd": "event", "type": "outage"})", "command.duration_s: missing"},
      {R"({"cmd": "event", "type": "imu", "duration_s": 1, "fault": "stuck"})", "command.sensor: missing"},
      {R"({"cmd": "event", "type": "truth", "duration_s": 1, "fault": "jump"})", "'jump' is not one of"},
      {R"({"cmd": "event", "type": "antenna", "duration_s": 1, "fault": "cut"})", "'cut' is not one of open, short"},
      {R"({"cmd": {"a": 1}})", "command.cmd"},
      {R"([1, 2])", "a command is one JSON object per line"},
      {R"({"cmd": )", "not a JSON object"},
      {"\"text\"", "a command is one JSON object per line"},
  };
  for (const auto& [line, why] : refused)
    EXPECT_NE(refusal(line).find(why), std::string::npos) << line << " -> " << refusal(line);
}

TEST(Control, RepliesAreAsciiJsonStrings) {
  EXPECT_EQ(json_string("plain"), "\"plain\"");
  EXPECT_EQ(json_string("a \"b\" \\ c"), R"("a \"b\" \\ c")");
  EXPECT_EQ(json_string("line\nnext\t"), R"("line\u000anext\u0009")");
  EXPECT_EQ(json_string("caf\xc3\xa9"), "\"caf??\"");
}

// A port whose client sent `in`; what navemu writes back collects in `out`.
class FakePort final : public transport::BytePort {
 public:
  std::string in, out;
  bool write(std::span<const std::uint8_t> c) override {
    out.append(reinterpret_cast<const char*>(c.data()), c.size());
    return true;
  }
  std::size_t read(std::span<std::uint8_t> buf) override {
    const std::size_t n = std::min(buf.size(), in.size());
    std::memcpy(buf.data(), in.data(), n);
    in.erase(0, n);
    return n;
  }
  std::string describe() const override { return "fake"; }
};

// 16 lines per tick at most (blank ones skipped, but counted), CR LF taken, an over-long line refused whole
// (also one that arrives over several reads) without losing the command after it.
TEST(Control, LinesAreFramedAndBoundedPerTick) {
  auto fake = std::make_unique<FakePort>();
  FakePort& f = *fake;
  ControlPort port(std::move(fake));
  std::vector<std::string> seen;
  const auto echo = [&](std::string_view line) {
    seen.emplace_back(line);
    return std::string("ok");
  };
  f.in = "\n\r\n";
  for (int i = 0; i < 20; ++i) f.in += fmt::format("c{}\r\n", i);  // (not +: GCC 12's false -Wrestrict)
  port.service(echo);
  ASSERT_EQ(seen.size(), 14u) << "16 lines, the 2 blank ones among them";
  EXPECT_EQ(seen.front(), "c0");
  EXPECT_EQ(seen.back(), "c13");
  port.service(echo);
  ASSERT_EQ(seen.size(), 20u);
  EXPECT_EQ(seen.back(), "c19");
  EXPECT_EQ(std::count(f.out.begin(), f.out.end(), '\n'), 20);

  f.out.clear();
  seen.clear();
  f.in = std::string(kMaxControlLine + 10, 'x') + "\nafter\n";
  port.service(echo);
  EXPECT_EQ(seen, std::vector<std::string>{"after"});
  EXPECT_NE(f.out.find("line longer than 4096 bytes"), std::string::npos) << f.out;

  f.out.clear();
  seen.clear();
  f.in = std::string(3 * kMaxControlLine, 'y');  // no end yet: refused now, the rest dropped
  port.service(echo);
  EXPECT_TRUE(seen.empty());
  EXPECT_NE(f.out.find("line longer"), std::string::npos);
  f.in = std::string(kMaxControlLine, 'y') + "\nlast\n";
  port.service(echo);
  EXPECT_EQ(seen, std::vector<std::string>{"last"});
}

}  // namespace
}  // namespace navemu
