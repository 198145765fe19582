#include "emulator/rinex_files.hpp"

#include <fmt/format.h>

#include <fstream>
#include <string>
#include <system_error>

#include "core/errors.hpp"

namespace navemu {

namespace {

std::string read_file(const std::filesystem::path& file) {
  const std::string name = file.string();
  auto fail = [&name](const std::string& problem) { throw InputError(name, 0, "", problem); };
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) fail("cannot open: no such file");
  if (std::filesystem::is_directory(file, ec)) fail("cannot open: is a directory");
  std::ifstream in(file, std::ios::binary);
  if (!in) fail("cannot open for reading");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  // Read whole: a bound, so that a wrong file is an error rather than memory exhausted. A day
  // of 1 Hz multi-GNSS observations is about 0.5 GB.
  constexpr std::streamoff kMaxBytes = std::streamoff{2} << 30;
  if (size > kMaxBytes)
    fail(fmt::format("{} bytes: over the 2 GiB a RINEX file may have here", size));
  std::string text;
  if (size > 0) {
    text.resize(static_cast<std::size_t>(size));
    in.read(text.data(), static_cast<std::streamsize>(size));
    if (in.gcount() != static_cast<std::streamsize>(size)) fail("read error");
  }
  return text;
}

}  // namespace

NavData read_rinex_nav(const std::filesystem::path& file) {
  return parse_rinex_nav(read_file(file), file.string());
}

ObsData read_rinex_obs(const std::filesystem::path& file) {
  return parse_rinex_obs(read_file(file), file.string());
}

}  // namespace navemu
