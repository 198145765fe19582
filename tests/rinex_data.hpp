#pragma once
// RINEX reference files (../shared/data) for tests, through the protocol readers. User-given
// files go through the emulator's reader, which checks them first (emulator/rinex_files.hpp).

#include <filesystem>
#include <fstream>

#include "protocols/rinex.hpp"

namespace navemu::test {

inline NavData rinex_nav_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return parse_rinex_nav(in, file.string());
}

inline ObsData rinex_obs_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return parse_rinex_obs(in, file.string());
}

}  // namespace navemu::test
