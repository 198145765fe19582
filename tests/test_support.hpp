#pragma once
// Shared helpers for tests: where the reference data lives, and skipping without it.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <sys/wait.h>
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

struct CommandResult {
  int exit_code = -1;
  std::string out;  // standard output
};

// Runs a shell command line (arguments already quoted by the caller) and captures its
// standard output; standard error passes through unless the command redirects it.
inline CommandResult run_command(const std::string& command_line) {
  CommandResult r;
  FILE* pipe = ::popen(command_line.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buf{};
  for (std::size_t n; (n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0;) r.out.append(buf.data(), n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// Single-quotes a string for the shell.
inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace navemu::test

// Skips the current test, with a message, when ../shared is not there.
#define NAVEMU_REQUIRE_SHARED()                                                     \
  do {                                                                              \
    if (::navemu::test::shared_dir().empty())                                       \
      GTEST_SKIP() << "../shared/data not found (set NAVEMU_SHARED): reference data " \
                      "test skipped";                                               \
  } while (0)
