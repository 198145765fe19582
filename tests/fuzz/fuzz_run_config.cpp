// The run configuration loader (emulator/run_config.hpp): a YAML file is loaded or refused with
// an InputError naming file, line and key. The file sits in a scratch folder of its own, so
// the relative paths it names resolve there (to files that do not exist).

#include <cstdint>

#include "emulator/run_config.hpp"
#include "core/errors.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file = navemu::fuzz::write_scratch("run.yaml", navemu::fuzz::text_of(data, size));
  try {
    (void)navemu::load_run_config(file);
  } catch (const navemu::InputError&) {
  }
  return 0;
}
