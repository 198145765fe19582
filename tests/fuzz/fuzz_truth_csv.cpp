// The truth CSV reader (emulator/truth_csv.hpp) over a whole file: every row is read and
// checked, or the file is refused with an InputError naming file, line and column; the rows it
// accepts are finite with strictly increasing time.

#include <cmath>
#include <cstdint>

#include "emulator/truth_csv.hpp"
#include "core/errors.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = navemu::fuzz::write_scratch("truth.csv", navemu::fuzz::text_of(data, size));
  try {
    navemu::TruthCsvReader reader(file.string());
    navemu::TruthRow row;
    double last_time_s = -INFINITY;
    while (reader.next(row)) {
      if (!(row.time_s > last_time_s) || !std::isfinite(row.time_s))
        navemu::fuzz::fail("an accepted row's time is not finite and increasing");
      if (!row.v_ned_mps.allFinite() || !row.rpy_rad.allFinite() || !std::isfinite(row.position.h_m))
        navemu::fuzz::fail("an accepted row holds a value that is not finite");
      last_time_s = row.time_s;
    }
  } catch (const navemu::InputError&) {
  }
  return 0;
}
