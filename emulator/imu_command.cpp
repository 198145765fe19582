// navemu imu (placeholder until implemented).

#include <ostream>

#include "emulator/commands.hpp"

namespace navemu {

struct ImuOptions {};

std::shared_ptr<ImuOptions> add_imu_command(CLI::App& app) {
  app.add_subcommand("imu", "(not yet available)");
  return std::make_shared<ImuOptions>();
}

int run_imu(const ImuOptions&, std::ostream&, std::ostream& err) {
  err << "navemu imu: not yet available\n";
  return 1;
}

}  // namespace navemu
