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
  std::vector<navemu::ImuFault> imu_faults;
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
      if (auto* e = std::get_if<navemu::ControlEvent>(&std::get<navemu::ControlCommand>(parsed))) {
        navemu::ControlEvent copy = *e;
        copy.events.for_each_window(check_window);
        for (const auto& f : copy.imu) check_window(f.window);
        for (const auto& f : copy.truth) check_window(f.window);
        if (accepted.size() < 64) accepted.append(copy.events);
        if (imu_faults.size() < 64) imu_faults.insert(imu_faults.end(), copy.imu.begin(), copy.imu.end());
      }
      return std::string("{\"ok\": true}");
    });
    if (lines > static_cast<std::size_t>(navemu::kMaxControlLinesPerTick)) std::abort();
  }
  for (const char c : memory.written)
    if (static_cast<unsigned char>(c) >= 0x80 || (static_cast<unsigned char>(c) < 0x20 && c != '\n')) std::abort();

  // Accepted IMU faults through a sensor model (those that do not fit it are refused, as the
  // IMU channel does).
  if (!imu_faults.empty()) {
    navemu::ImuParams p;
    p.internal_rate_hz = p.output_rate_hz = 100.0;
    std::erase_if(imu_faults, [&](const navemu::ImuFault& f) { return !navemu::fault_fits(f, p); });
    navemu::ImuModel model(p, 1);
    model.set_faults(imu_faults, navemu::GpsTime{0});
    navemu::ImuSample out;
    for (std::int64_t n = 0; n < 300; ++n) model.step(navemu::GpsTime{n * 10'000'000}, navemu::IdealImu{}, 25.0, out);
  }
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
