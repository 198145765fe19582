// navemu ctl: sends live-control commands (emulator/control.hpp) to a running navemu's control
// port and prints the replies.

#include <fmt/format.h>

#include <iostream>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "emulator/commands.hpp"
#include "transports/tcp_request.hpp"

namespace navemu {

struct CtlOptions {
  std::string address = "127.0.0.1";
  int port = 0;
  double timeout_s = 5.0;
  std::vector<std::string> commands;
};

std::shared_ptr<CtlOptions> add_ctl_command(CLI::App& app) {
  auto opt = std::make_shared<CtlOptions>();
  CLI::App* cmd = app.add_subcommand("ctl", "Send live-control commands (faults, events) to a running navemu");
  cmd->footer(
      "Sends each COMMAND (or, without any, each line of standard input) to the control port of\n"
      "a running `navemu run` (configuration `control: {port: N}`; navemu prints the port at\n"
      "start) and prints one reply line per command. A command is one JSON object:\n"
      "  {\"cmd\": \"event\", \"type\": \"jamming\", \"duration_s\": 10, \"j_over_s_db\": 45}\n"
      "      an event with the keys of `events:` (configs/default.yaml: jamming, outage,\n"
      "      antenna, satellite, spoofing, ionosphere, multipath, cable, reset, imu, truth);\n"
      "      its start_s counts from the next GNSS epoch (the next IMU sample without a\n"
      "      receiver; 0 when absent),\n"
      "      or \"at\" gives its start as GPS time (ISO-8601 UTC or WEEK:TOW)\n"
      "  {\"cmd\": \"clear\"}   ends every event, those of the configuration too\n"
      "A reply is {\"ok\": true, \"from\": UTC, \"gps\": WEEK:TOW} or {\"ok\": false, \"error\": WHY}.\n"
      "Exit code 0 when every command was accepted, 1 when one was refused or unanswered, 2 when\n"
      "the port cannot be reached.\n"
      "Example: navemu ctl --port 7780 '{\"cmd\": \"event\", \"type\": \"outage\", \"duration_s\": 5}'");
  cmd->add_option("--port", opt->port, "navemu's control port")->required()->check(CLI::Range(1, 65535));
  cmd->add_option("--address", opt->address, "Its numeric address")->capture_default_str();
  cmd->add_option("--timeout", opt->timeout_s, "Seconds to wait for the replies")
      ->capture_default_str()
      ->check(positive_number());
  cmd->add_option("command", opt->commands, "JSON commands; none: read them from standard input");
  return opt;
}

int run_ctl(const CtlOptions& opt, std::ostream& out, std::ostream& err) {
  std::vector<std::string> lines = opt.commands;
  if (lines.empty())
    for (std::string l; std::getline(std::cin, l);)
      if (!l.empty()) lines.push_back(l);
  std::vector<std::string> replies;
  try {
    replies = transport::tcp_request_lines(opt.address, opt.port, lines, lines.size(), opt.timeout_s);
  } catch (const std::runtime_error& e) {
    err << "navemu ctl: " << e.what() << "\n";
    return 2;
  }
  bool all_ok = replies.size() == lines.size();
  for (const std::string& r : replies) {
    out << r << "\n";
    all_ok = all_ok && r.find("\"ok\": true") != std::string::npos;
  }
  if (replies.size() < lines.size())
    err << fmt::format("navemu ctl: {} of {} commands unanswered within {} s\n", lines.size() - replies.size(),
                       lines.size(), opt.timeout_s);
  return all_ok ? 0 : 1;
}

}  // namespace navemu
