// navemu allan (placeholder until implemented).

#include <ostream>

#include "emulator/commands.hpp"

namespace navemu {

struct AllanOptions {};

std::shared_ptr<AllanOptions> add_allan_command(CLI::App& app) {
  app.add_subcommand("allan", "(not yet available)");
  return std::make_shared<AllanOptions>();
}

int run_allan(const AllanOptions&, std::ostream&, std::ostream& err) {
  err << "navemu allan: not yet available\n";
  return 1;
}

}  // namespace navemu
