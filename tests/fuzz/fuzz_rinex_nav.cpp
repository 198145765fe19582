// The RINEX navigation reader (protocols/rinex.hpp, RINEX 2.11 / 3.0x): the file is parsed or
// refused with an InputError naming file, line and field; then each GPS record it accepts is
// selected and evaluated at its toe and two hours on (IS-GPS-200 20.3.3.4.3), as the emulator
// would use it, each QZSS, Galileo and BeiDou record alike and each GLONASS state vector
// integrated over 15 min, which must not crash or hang whatever the orbit's numbers.

#include <cstdint>
#include <sstream>
#include <string>

#include "core/errors.hpp"
#include "models/orbit.hpp"
#include "protocols/rinex.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(navemu::fuzz::text_of(data, size)));
  navemu::NavData nav;
  try {
    nav = navemu::parse_rinex_nav(in, "fuzz.nav");
  } catch (const navemu::InputError&) {
    return 0;
  }
  for (const navemu::GpsEphemeris& eph : nav.gps) {
    for (const double dt_s : {0.0, 7200.0}) {
      const navemu::GpsTime t = eph.toe.plus_s(dt_s);
      if (const navemu::GpsEphemeris* chosen = navemu::select_ephemeris(nav, eph.sat, t))
        (void)navemu::gps_sat_state(*chosen, t);
      (void)navemu::gps_sat_clock_poly_s(eph, t);
    }
  }
  // The other systems' Kepler records, each at its toe and two hours on (BeiDou GEOs too).
  const auto evaluate = [](const auto& records) {
    for (const auto& eph : records)
      for (const double dt_s : {0.0, 7200.0}) (void)navemu::broadcast_sat_state(eph, eph.toe.plus_s(dt_s));
  };
  evaluate(nav.qzss);
  evaluate(nav.galileo);
  evaluate(nav.beidou);
  for (const navemu::GlonassEphemeris& eph : nav.glonass)
    for (const double dt_s : {0.0, 900.0}) (void)navemu::glonass_sat_state(eph, eph.tb.plus_s(dt_s));
  return 0;
}
