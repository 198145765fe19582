// The RINEX observation reader (protocols/rinex.hpp, RINEX 2.11 / 3.0x): the file is parsed or
// refused with an InputError naming file, line and field; every satellite it accepts carries
// one value, loss-of-lock and signal-strength indicator per observation type of its system.

#include <cstdint>
#include <sstream>
#include <string>

#include "core/errors.hpp"
#include "protocols/rinex.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(navemu::fuzz::text_of(data, size)));
  try {
    const navemu::ObsData obs = navemu::parse_rinex_obs(in, "fuzz.obs");
    for (const navemu::ObsEpoch& epoch : obs.epochs)
      for (const navemu::SatObs& sat : epoch.sats) {
        const auto types = obs.header.types.find(sat.system);
        const std::size_t n = types == obs.header.types.end() ? 0 : types->second.size();
        if (sat.values.size() != n || sat.lli.size() != n || sat.ssi.size() != n)
          navemu::fuzz::fail("a satellite's values do not match its system's observation types");
      }
  } catch (const navemu::InputError&) {
  }
  return 0;
}
