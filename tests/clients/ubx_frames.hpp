#pragma once
// UBX frames of a byte stream (navemu's gnss.capture and CAPTURE.in, a `file` output, pty
// reads), split and checked with the project's parser (protocols/ubx.hpp) and decoded with its
// message descriptions (protocols/ubx_messages.hpp).

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "protocols/ubx.hpp"
#include "protocols/ubx_messages.hpp"

namespace navemu::test::clients {

struct UbxFrame {
  ubx::MsgId id;
  std::vector<std::uint8_t> payload;
  double t_mono = 0;  // arrival (pty reads); 0 for frames from a file
};

// Every good frame of a byte stream (NMEA and junk in between are skipped).
inline std::vector<UbxFrame> parse_frames(const std::string& bytes,
                                          ubx::Parser::Counters* counters = nullptr) {
  ubx::Parser p(65535);
  std::vector<UbxFrame> out;
  p.feed(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()),
         [&](ubx::Parser::Result r) {
           if (r != ubx::Parser::Result::kFrame) return;
           out.push_back({{p.cls(), p.id()}, {p.payload().begin(), p.payload().end()}, 0.0});
         });
  if (counters != nullptr) *counters = p.counters();
  return out;
}

template <typename Msg>
std::vector<Msg> decode_all(const std::vector<UbxFrame>& frames, ubx::MsgId id) {
  std::vector<Msg> out;
  for (const UbxFrame& f : frames) {
    Msg m;
    if (f.id == id && ubx::decode(f.payload, m)) out.push_back(m);
  }
  return out;
}

}  // namespace navemu::test::clients
