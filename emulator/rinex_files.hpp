#pragma once
// RINEX files from disk for the readers of protocols/rinex.hpp: the file is checked and read
// whole, then parsed. Every error is an InputError naming the file (and the line and field
// when the content is at fault).

#include <filesystem>

#include "protocols/rinex.hpp"

namespace navemu {

NavData read_rinex_nav(const std::filesystem::path& file);
ObsData read_rinex_obs(const std::filesystem::path& file);

}  // namespace navemu
