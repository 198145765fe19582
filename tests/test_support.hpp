#pragma once
// Shared helpers for tests: where the reference data lives, skipping without it, running
// commands, and reading RTKLIB rnx2rtkp output.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <sys/wait.h>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/errors.hpp"
#include "core/satellite.hpp"
#include "core/time.hpp"
#include "models/geodesy.hpp"

namespace navemu::test {

// ../shared next to the repository, or $NAVEMU_SHARED. Empty when absent.
inline std::filesystem::path shared_dir() {
  const char* env = std::getenv("NAVEMU_SHARED");
  std::filesystem::path p = env != nullptr ? std::filesystem::path(env)
                                           : std::filesystem::path(NAVEMU_SHARED_DEFAULT);
  return std::filesystem::is_directory(p / "data") ? p : std::filesystem::path{};
}

// The whole content of a file ("" when it cannot be opened).
inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline std::filesystem::path shared_data(const std::string& relative) {
  return shared_dir() / "data" / relative;
}

// Runs `f`, expecting an InputError at `line` naming `field`; returns its message.
inline std::string expect_input_error(const std::function<void()>& f, int line, const std::string& field) {
  try {
    f();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected InputError at line " << line << " (" << field << "), none thrown";
  return {};
}

// The first `n` satellites the systems define, in SatId order (GPS PRN 1-63, then SBAS, ...),
// for tests that need many independent satellites.
inline std::vector<SatId> first_satellites(std::size_t n) {
  std::vector<SatId> out;
  for (const GnssSystemInfo& s : kGnssSystems)
    for (int k = s.first_number; k <= s.last_number && out.size() < n; ++k)
      out.emplace_back(s.system, k);
  return out;
}

// The built navemu executable.
inline std::filesystem::path navemu_binary() {
  return std::filesystem::path(NAVEMU_BINARY_DIR) / "emulator" / "navemu";
}

// The full path of a program: PATH first, then /usr/sbin and /sbin (Debian installs gpsd in
// /usr/sbin, which an unprivileged user's PATH may lack). Empty when not found.
inline std::string find_program(const std::string& name) {
  std::string dirs = std::getenv("PATH") != nullptr ? std::getenv("PATH") : "";
  dirs += ":/usr/sbin:/sbin";
  std::stringstream ss(dirs);
  for (std::string d; std::getline(ss, d, ':');) {
    if (d.empty()) continue;
    const std::filesystem::path p = std::filesystem::path(d) / name;
    if (::access(p.c_str(), X_OK) == 0 && std::filesystem::is_regular_file(p)) return p.string();
  }
  return {};
}

// A CSV file with a header row, read whole; its cells are found by column name, so that tests
// do not depend on the order of columns. An unknown column throws std::out_of_range naming it.
class CsvTable {
 public:
  explicit CsvTable(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read " + path.string());
    std::string line;
    std::getline(in, line);
    header_ = split(line);
    while (std::getline(in, line)) rows_.push_back(split(line));
  }
  std::size_t size() const { return rows_.size(); }  // data rows, the header not counted
  const std::vector<std::string>& header() const { return header_; }
  const std::vector<std::string>& row(std::size_t i) const { return rows_.at(i); }
  // The cell of data row i (from 0) in `column`, as text, a number or an integer.
  const std::string& operator()(std::size_t i, std::string_view column) const {
    const std::vector<std::string>& r = rows_.at(i);
    const std::size_t c = index(column);
    static const std::string empty;
    return c < r.size() ? r[c] : empty;
  }
  double num(std::size_t i, std::string_view column) const { return std::stod((*this)(i, column)); }
  std::int64_t integer(std::size_t i, std::string_view column) const { return std::stoll((*this)(i, column)); }

 private:
  static std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    if (!line.empty() && line.back() == ',') f.emplace_back();
    return f;
  }
  std::size_t index(std::string_view column) const {
    for (std::size_t c = 0; c < header_.size(); ++c)
      if (header_[c] == column) return c;
    throw std::out_of_range("no column " + std::string(column));
  }
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

struct CommandResult {
  int exit_code = -1;
  std::string out;  // standard output
};

// Runs a shell command line (arguments already quoted by the caller) and captures its
// standard output; standard error passes through unless the command redirects it.
inline CommandResult run_command(const std::string& command_line) {
  CommandResult r;
  FILE* pipe = ::popen(command_line.c_str(), "r");
  if (pipe == nullptr) return r;
  std::array<char, 4096> buf{};
  for (std::size_t n; (n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0;) r.out.append(buf.data(), n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// Single-quotes a string for the shell.
inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// One solution of RTKLIB rnx2rtkp's -e (ECEF) output, tagged with its GPS time of week.
struct RtklibFix {
  double gps_tow_s = 0.0;
  Vec3 p_ecef_m = Vec3::Zero();
};

// Reads a rnx2rtkp -e .pos file: "yyyy/mm/dd hh:mm:ss.sss x y z ..." (GPS time) or
// "week tow x y z ..." lines; '%' lines are comments.
inline std::vector<RtklibFix> read_rtklib_ecef_pos(const std::filesystem::path& file) {
  std::vector<RtklibFix> out;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '%') continue;
    int y, mo, d, h, mi;
    double s, x, yy, z;
    if (std::sscanf(line.c_str(), "%d/%d/%d %d:%d:%lf %lf %lf %lf", &y, &mo, &d, &h, &mi, &s, &x,
                    &yy, &z) == 9) {
      const WeekTow wt = to_week_tow(gps_from_calendar(CalendarTime{y, mo, d, h, mi, s}));
      out.push_back({wt.tow_s, Vec3(x, yy, z)});
      continue;
    }
    int week;
    double tow;
    if (std::sscanf(line.c_str(), "%d %lf %lf %lf %lf", &week, &tow, &x, &yy, &z) == 5)
      out.push_back({tow, Vec3(x, yy, z)});
  }
  return out;
}

}  // namespace navemu::test

// Skips the current test, with a message, when ../shared is not there.
#define NAVEMU_REQUIRE_SHARED()                                                     \
  do {                                                                              \
    if (::navemu::test::shared_dir().empty())                                       \
      GTEST_SKIP() << "../shared/data not found (set NAVEMU_SHARED): reference data " \
                      "test skipped";                                               \
  } while (0)
