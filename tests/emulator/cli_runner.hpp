#pragma once
// Runs the navemu command line in-process for tests: exit code, standard output and error.

#include <sstream>
#include <string>
#include <vector>

#include "emulator/cli.hpp"

namespace navemu::test {

struct CliRun {
  int code = -1;
  std::string out, err;
};

inline CliRun navemu(std::vector<std::string> args) {
  args.insert(args.begin(), "navemu");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  std::ostringstream out, err;
  CliRun r;
  r.code = run_cli(static_cast<int>(argv.size()), argv.data(), out, err);
  r.out = out.str();
  r.err = err.str();
  return r;
}

}  // namespace navemu::test
