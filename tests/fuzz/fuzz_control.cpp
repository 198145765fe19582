// The live-control port (emulator/control.hpp), as `navemu run` reads it from TCP clients: the
// input arrives in pieces of 1..64 bytes (the first byte chooses). Every line gets at most one
// reply, at most kMaxControlLinesPerTick per service call, each a one-line ASCII JSON object;
// every accepted event has the window the configuration would accept; and the accepted events
// act on a measurement generator (a nominal sky, three epochs) without a crash.

#include <algorithm>
#include <cmath>
#include <memory>

#include "emulator/control.hpp"
#include "models/constellation.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

using navemu::fuzz::MemoryPort;

void check_window(const navemu::EventWindow& w) {
  if (!(std::isfinite(w.start_s) && w.start_s >= 0.0 && w.duration_s > 0.0 && std::isfinite(w.duration_s) &&
        w.ramp_s >= 0.0 && 2.0 * w.ramp_s <= w.duration_s))
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  auto port = std::make_unique<MemoryPort>();
  MemoryPort& memory = *port;
  navemu::ControlPort control(std::move(port));
  const std::size_t piece = 1 + (data[0] & 0x3F);
  auto input = navemu::fuzz::bytes_of(data + 1, size - 1);
  navemu::GnssEvents accepted;
  while (!input.empty()) {
    const std::size_t n = std::min(piece, input.size());
    memory.pending = input.first(n);
    input = input.subspan(n);
    std::size_t lines = 0;
    control.service([&](std::string_view line) {
      ++lines;
      const auto parsed = navemu::parse_control_line(line);
      if (const std::string* why = std::get_if<std::string>(&parsed))
        return "{\"ok\": false, \"error\": " + navemu::json_string(*why) + "}";
      if (const auto* e = std::get_if<navemu::ControlEvent>(&std::get<navemu::ControlCommand>(parsed))) {
        for (const auto& j : e->events.jamming) check_window(j.window);
        for (const auto& o : e->events.outages) check_window(o.window);
        for (const auto& a : e->events.antenna) check_window(a.window);
        for (const auto& s : e->events.satellites) check_window(s.window);
        if (accepted.size() < 64) accepted.append(e->events);
      }
      return std::string("{\"ok\": true}");
    });
    if (lines > static_cast<std::size_t>(navemu::kMaxControlLinesPerTick)) std::abort();
  }
  for (const char c : memory.written)
    if (static_cast<unsigned char>(c) >= 0x80 || (static_cast<unsigned char>(c) < 0x20 && c != '\n')) std::abort();

  if (accepted.size() == 0) return 0;
  static const navemu::GpsTime t0 = navemu::from_week_tow(2244, 36000.0);
  static const navemu::NavData nav = navemu::nominal_constellation(t0);
  navemu::MeasurementConfig cfg;
  cfg.errors = navemu::ErrorSwitches{false, false, false, false, false, false};
  navemu::MeasurementGenerator gen(nav, cfg);
  gen.set_event_origin(t0);
  gen.add_events(accepted);
  const navemu::Vec3 p = navemu::ecef_from_geodetic(navemu::Geodetic{32.3, -90.9, 60.0});
  for (const double t : {0.0, 1.0, 30.0}) gen.generate(t0.plus_s(t), p);
  return 0;
}
