#include "emulator/cli.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <ostream>

#include "emulator/commands.hpp"
#include "core/errors.hpp"

#ifndef NAVEMU_VERSION
#define NAVEMU_VERSION "unknown"
#endif

namespace navemu {

int run_cli(int argc, char** argv, std::ostream& out, std::ostream& err) {
  CLI::App app{
      "navemu - hardware-in-the-loop emulator of GNSS receivers and MEMS IMUs.\n"
      "Times are ISO-8601 UTC (2023-01-08T09:59:42Z) or GPS WEEK:TOW (2244:36000)."};
  app.name("navemu");
  app.set_version_flag("--version", std::string("navemu ") + NAVEMU_VERSION);
  app.require_subcommand(0, 1);
  app.footer("Run 'navemu help SUBCOMMAND' (or 'navemu SUBCOMMAND --help') for the options and\n"
             "output of each subcommand; 'navemu profiles' lists the receiver and IMU profiles and\n"
             "the ready scenarios.");

  const auto run = add_run_command(app);
  const auto simulate = add_simulate_command(app);
  SkyOptions sky;
  add_sky_command(app, sky);
  SppOptions spp;
  add_spp_command(app, spp);
  ObsOptions obs;
  add_obs_command(app, obs);
  const auto imu = add_imu_command(app);
  const auto allan = add_allan_command(app);
  const auto deadreckon = add_deadreckon_command(app);
  const auto scene = add_scene_command(app);
  const auto ctl = add_ctl_command(app);
  app.add_subcommand("profiles", "List the GNSS receiver and IMU profiles and the ready scenarios");
  std::string help_topic;
  app.add_subcommand("help", "Print this list, or the help of one subcommand")
      ->add_option("subcommand", help_topic, "The subcommand to explain");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version (exit code 0) print to `out`; usage errors to `err`, exit 2.
    const int code = app.exit(e, out, err);
    return code == 0 ? 0 : 2;
  }

  // `navemu` alone and `navemu help`: the command list; `navemu help SUBCOMMAND`: its help.
  if (app.get_subcommands().empty() || app.got_subcommand("help")) {
    if (help_topic.empty()) {
      // Not app.help(), which would explain the selected subcommand (help) instead.
      out << app.get_formatter()->make_help(&app, "navemu", CLI::AppFormatMode::Normal);
      return 0;
    }
    try {
      out << app.get_subcommand(help_topic)->help();
      return 0;
    } catch (const CLI::OptionNotFound&) {
      err << "navemu help: no subcommand '" << help_topic << "' (navemu help lists them)\n";
      return 2;
    }
  }

  try {
    if (app.got_subcommand("profiles")) return run_profiles(out);
    if (app.got_subcommand("run")) return run_run(*run, out, err);
    if (app.got_subcommand("simulate")) return run_run(*simulate, out, err);
    if (app.got_subcommand("sky")) return run_sky(sky, out, err);
    if (app.got_subcommand("spp")) return run_spp(spp, out, err);
    if (app.got_subcommand("obs")) return run_obs(obs, out, err);
    if (app.got_subcommand("imu")) return run_imu(*imu, out, err);
    if (app.got_subcommand("allan")) return run_allan(*allan, out, err);
    if (app.got_subcommand("deadreckon")) return run_deadreckon(*deadreckon, out, err);
    if (app.got_subcommand("scene")) return run_scene(*scene, out, err);
    if (app.got_subcommand("ctl")) return run_ctl(*ctl, out, err);
  } catch (const InputError& e) {
    err << "navemu: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    err << "navemu: error: " << e.what() << "\n";
    return 1;
  }
  return 2;
}

}  // namespace navemu
