#pragma once
#include <iosfwd>

namespace navemu {
// Runs the navemu command line; returns the process exit code.
int run_cli(int argc, char** argv, std::ostream& out, std::ostream& err);
}  // namespace navemu
