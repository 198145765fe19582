// navemu deadreckon (placeholder until implemented).

#include <ostream>

#include "emulator/commands.hpp"

namespace navemu {

struct DeadreckonOptions {};

std::shared_ptr<DeadreckonOptions> add_deadreckon_command(CLI::App& app) {
  app.add_subcommand("deadreckon", "(not yet available)");
  return std::make_shared<DeadreckonOptions>();
}

int run_deadreckon(const DeadreckonOptions&, std::ostream&, std::ostream& err) {
  err << "navemu deadreckon: not yet available\n";
  return 1;
}

}  // namespace navemu
