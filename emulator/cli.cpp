#include "emulator/cli.hpp"

#include <ostream>

namespace navemu {
int run_cli(int, char**, std::ostream&, std::ostream&) { return 0; }
}  // namespace navemu
