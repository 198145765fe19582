// RINEX files read from disk (emulator/rinex_files.hpp): a file that cannot be read is an
// InputError naming it. The readers' handling of the content: tests/protocols/test_rinex.cpp;
// the size bound: test_input_limits.cpp.

#include <gtest/gtest.h>

#include <string>

#include "emulator/rinex_files.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

using test::expect_input_error;

TEST(RinexNavErrors, MissingFile) {
  const std::string msg = expect_input_error(
      [] { (void)read_rinex_nav("/nonexistent/dir/none.05n"); }, 0, "");
  EXPECT_NE(msg.find("/nonexistent/dir/none.05n"), std::string::npos) << msg;
}

TEST(RinexObsErrors, MissingFile) {
  expect_input_error([] { (void)read_rinex_obs("/nonexistent/none.05o"); }, 0, "");
}

}  // namespace
}  // namespace navemu
