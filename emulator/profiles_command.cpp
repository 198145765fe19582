// navemu profiles: what the configuration can name, one line each: the GNSS receiver profiles
// (configs/gnss/, gnss.profile), the IMU profiles (configs/imu/, imu.profile) and the ready
// scenarios (configs/*.yaml, navemu run configs/NAME.yaml), each with its description.

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <ostream>

#include "emulator/commands.hpp"
#include "emulator/imu_profile.hpp"
#include "emulator/run_config.hpp"

namespace navemu {

namespace {

// "  name   description", or the reason the file does not load in its place.
void list(std::ostream& out, const std::vector<std::string>& names,
          const std::function<std::string(const std::string&)>& describe) {
  std::size_t width = 0;
  for (const std::string& n : names) width = std::max(width, n.size());
  for (const std::string& n : names) {
    std::string text;
    try {
      text = describe(n);
    } catch (const std::exception& e) {
      text = std::string("does not load: ") + e.what();
    }
    fmt::print(out, "  {:<{}}  {}\n", n, width, text);
  }
}

// Scenario files under configs/ ("default", "mission/high"): every .yaml but the profiles and
// the material tables.
std::vector<std::string> ready_scenarios() {
  std::vector<std::string> names;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(config_dir(), ec);
       it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    const std::string folder = it->path().filename().string();
    if (it->is_directory() && (folder == "gnss" || folder == "imu" || folder == "scenes")) {
      it.disable_recursion_pending();
      continue;
    }
    if (it->is_regular_file() && it->path().extension() == ".yaml")
      names.push_back(std::filesystem::relative(it->path(), config_dir()).replace_extension().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

int run_profiles(std::ostream& out) {
  fmt::print(out, "GNSS receiver profiles ({}, gnss.profile):\n", (config_dir() / "gnss").string());
  list(out, available_gnss_profiles(), [](const std::string& n) { return load_gnss_profile(n).description; });
  fmt::print(out, "IMU profiles ({}, imu.profile):\n", (config_dir() / "imu").string());
  list(out, available_imu_profiles(), [](const std::string& n) { return load_imu_profile(n).description; });
  fmt::print(out, "Ready scenarios (navemu run {}/NAME.yaml):\n", config_dir().string());
  list(out, ready_scenarios(), [](const std::string& n) {
    return load_run_config(config_dir() / (n + ".yaml")).description;
  });
  return 0;
}

}  // namespace navemu
