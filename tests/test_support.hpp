#pragma once
// Shared helpers for tests: where the reference data lives, and skipping without it.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace navemu::test {

// ../shared next to the repository, or $NAVEMU_SHARED. Empty when absent.
inline std::filesystem::path shared_dir() {
  const char* env = std::getenv("NAVEMU_SHARED");
  std::filesystem::path p = env != nullptr ? std::filesystem::path(env)
                                           : std::filesystem::path(NAVEMU_SHARED_DEFAULT);
  return std::filesystem::is_directory(p / "data") ? p : std::filesystem::path{};
}

inline std::filesystem::path shared_data(const std::string& relative) {
  return shared_dir() / "data" / relative;
}

// The built navemu executable.
inline std::filesystem::path navemu_binary() {
  return std::filesystem::path(NAVEMU_BINARY_DIR) / "emulator" / "navemu";
}

}  // namespace navemu::test

// Skips the current test, with a message, when ../shared is not there.
#define NAVEMU_REQUIRE_SHARED()                                                     \
  do {                                                                              \
    if (::navemu::test::shared_dir().empty())                                       \
      GTEST_SKIP() << "../shared/data not found (set NAVEMU_SHARED): reference data " \
                      "test skipped";                                               \
  } while (0)
