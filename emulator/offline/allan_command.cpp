// navemu allan: overlapping Allan deviation of the columns of an IMU CSV file (as written by
// navemu imu), the IEEE-Std-952 noise terms read from each curve, and an optional log-log plot
// drawn by gnuplot.

#include <fcntl.h>
#include <fmt/format.h>
#include <fmt/ostream.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "emulator/commands.hpp"
#include "emulator/numeric_csv.hpp"
#include "models/allan.hpp"
#include "core/errors.hpp"

namespace navemu {

struct AllanOptions {
  std::string file;
  std::vector<std::string> columns;  // empty: the six sensor columns
  std::optional<double> rate_hz;     // unset: from the time_s column
  int points_per_decade = 10;
  std::string png_file;  // empty: no plot
  std::string out_file;  // empty: no CSV; "-": CSV on stdout (the table then goes to stderr)
};

namespace {

constexpr std::array<std::string_view, 6> kSensorColumns = {
    "f_x_mps2", "f_y_mps2", "f_z_mps2", "w_x_radps", "w_y_radps", "w_z_radps"};
constexpr std::string_view kTimeColumn = "time_s";
constexpr std::size_t kMinRows = 10;
// Largest departure of a time step from the mean step, as a fraction of it, that still counts
// as uniform sampling (covers the rounding of printed times).
constexpr double kStepTolerance = 0.01;

// What a column measures, from the unit in its name (../shared/DESIGN.md: units in names).
enum class Kind { gyro, accel, other };

Kind kind_of(std::string_view name) {
  if (name.ends_with("_radps")) return Kind::gyro;
  if (name.ends_with("_mps2")) return Kind::accel;
  return Kind::other;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

struct Table {
  std::vector<std::string> names;          // the requested columns
  std::vector<std::vector<double>> data;   // one vector per requested column
  std::vector<double> time_s;              // empty when not read
  std::vector<int> lines;                  // file line of each row (for time errors)
};

// Reads the requested columns (and time_s when `want_time`) of a CSV file with a header row
// through the shared numeric reader (file:line:column errors).
Table read_columns(const std::string& path, const std::vector<std::string>& wanted,
                   bool want_time) {
  const std::string time_name(kTimeColumn);
  NumericCsvReader csv(path, wanted, want_time ? std::vector<std::string>{time_name}
                                               : std::vector<std::string>{});
  if (want_time && !csv.has(time_name))
    throw InputError(path, csv.line(), time_name,
                     "no such column: give the sample rate with --rate");
  Table table;
  table.names = wanted;
  table.data.assign(wanted.size(), {});
  std::vector<double> values;
  while (csv.next(values)) {
    for (std::size_t c = 0; c < wanted.size(); ++c) table.data[c].push_back(values[c]);
    if (want_time) table.time_s.push_back(values.back());
    table.lines.push_back(csv.line());
  }
  const std::size_t rows = table.lines.size();
  if (rows < kMinRows)
    throw InputError(path, csv.line(), "",
                     fmt::format("{} data rows: the Allan deviation needs at least {}", rows,
                                 kMinRows));
  return table;
}

// The sampling interval from time_s: the mean step, after checking that time increases and
// that every step is within kStepTolerance of the mean (Allan variance assumes uniform
// sampling, IEEE Std 952-1997 C.2).
double sampling_interval(const std::string& path, const Table& t) {
  const std::vector<double>& ts = t.time_s;
  const std::string name(kTimeColumn);
  for (std::size_t i = 1; i < ts.size(); ++i)
    if (!(ts[i] > ts[i - 1]))
      throw InputError(path, t.lines[i], name,
                       fmt::format("time {} s does not increase (previous row {} s)", ts[i],
                                   ts[i - 1]));
  const double dt = (ts.back() - ts.front()) / static_cast<double>(ts.size() - 1);
  for (std::size_t i = 1; i < ts.size(); ++i) {
    const double step = ts[i] - ts[i - 1];
    if (std::abs(step - dt) > kStepTolerance * dt)
      throw InputError(path, t.lines[i], name,
                       fmt::format("non-uniform sampling: step {:.9g} s, mean step {:.9g} s "
                                   "(resample, or give the rate with --rate)",
                                   step, dt));
  }
  return dt;
}

std::string si_unit(Kind k) {
  switch (k) {
    case Kind::gyro: return "rad/s";
    case Kind::accel: return "m/s^2";
    case Kind::other: break;
  }
  return "unit";
}

// The fitted terms, in SI and in datasheet units (models/allan.hpp gives the conversions).
void print_fits(std::ostream& os, const std::vector<std::string>& names,
                const std::vector<AllanFit>& fits) {
  std::size_t w = 6;
  for (const std::string& n : names) w = std::max(w, n.size());
  fmt::print(os, "{:<{}}  {:>26}  {:>26}  {:>10}  {:>26}\n", "column", w, "white noise N",
             "bias instability B", "B at tau_s", "random walk K");
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string u = si_unit(kind_of(names[i]));
    const AllanFit& f = fits[i];
    const std::string k = f.random_walk > 0.0
                              ? fmt::format("{:.4g} {}/s/sqrt(Hz)", f.random_walk, u)
                              : std::string("-");
    fmt::print(os, "{:<{}}  {:>26}  {:>26}  {:>10.4g}  {:>26}\n", names[i], w,
               fmt::format("{:.4g} {}/sqrt(Hz)", f.white_density, u),
               fmt::format("{:.4g} {}", f.bias_instability, u), f.bias_instability_tau_s, k);
  }
  bool any = false;
  for (const std::string& n : names) any = any || kind_of(n) != Kind::other;
  if (!any) return;
  fmt::print(os, "datasheet units:\n");
  fmt::print(os, "{:<{}}  {:>26}  {:>26}  {:>10}  {:>26}\n", "column", w, "ARW / VRW",
             "bias instability", "", "RRW / AccRW");
  for (std::size_t i = 0; i < names.size(); ++i) {
    const Kind kind = kind_of(names[i]);
    if (kind == Kind::other) continue;
    const AllanFit& f = fits[i];
    std::string n, b, k;
    if (kind == Kind::gyro) {
      n = fmt::format("{:.4g} deg/sqrt(h)", arw_deg_per_sqrt_h(f.white_density));
      b = fmt::format("{:.4g} deg/h", gyro_bias_instability_deg_per_h(f.bias_instability));
      k = fmt::format("{:.4g} deg/h/sqrt(h)", rrw_deg_per_h_per_sqrt_h(f.random_walk));
    } else {
      n = fmt::format("{:.4g} m/s/sqrt(h)", vrw_mps_per_sqrt_h(f.white_density));
      b = fmt::format("{:.4g} mg", accel_bias_instability_mg(f.bias_instability));
      k = fmt::format("{:.4g} m/s/h^1.5", accrw_mps_per_h_1p5(f.random_walk));
    }
    if (!(f.random_walk > 0.0)) k = "-";
    fmt::print(os, "{:<{}}  {:>26}  {:>26}  {:>10}  {:>26}\n", names[i], w, n, b, "", k);
  }
}

void write_csv(std::ostream& os, const std::vector<std::string>& names,
               const std::vector<std::vector<AllanPoint>>& curves) {
  fmt::print(os, "tau_s");
  for (const std::string& n : names) fmt::print(os, ",{}", n);
  fmt::print(os, "\n");
  for (std::size_t r = 0; r < curves.front().size(); ++r) {
    fmt::print(os, "{:.9g}", curves.front()[r].tau_s);
    for (const auto& c : curves) fmt::print(os, ",{:.9g}", c[r].adev);
    fmt::print(os, "\n");
  }
}

// gnuplot from PATH; empty when there is none.
std::filesystem::path find_gnuplot() {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return {};
  std::string_view rest(path);
  while (true) {
    const std::size_t colon = rest.find(':');
    const std::string_view dir = rest.substr(0, colon);
    if (!dir.empty()) {
      const std::filesystem::path p = std::filesystem::path(dir) / "gnuplot";
      std::error_code ec;
      if (std::filesystem::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0) return p;
    }
    if (colon == std::string_view::npos) break;
    rest.remove_prefix(colon + 1);
  }
  return {};
}

std::string gnuplot_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("''") : std::string(1, c);
  return q + "'";
}

// Runs `argv` without a shell (posix_spawn), its stdout and stderr into `output`; the exit
// status as waitpid gives it, -1 when it could not be started.
int run_capturing(const std::vector<std::string>& argv, std::string& output) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) return -1;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDERR_FILENO);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  const int rc = ::posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  if (rc != 0) {
    ::close(fds[0]);
    output = std::strerror(rc);
    return -1;
  }
  std::array<char, 4096> buf{};
  for (ssize_t n; (n = ::read(fds[0], buf.data(), buf.size())) != 0;) {
    if (n > 0) output.append(buf.data(), static_cast<std::size_t>(n));
    else if (errno != EINTR) break;
  }
  ::close(fds[0]);
  int status = -1;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

std::atomic<int> script_counter{0};

// A log-log plot of the curves, one panel for the gyroscopes and one for the accelerometers
// (and one for other columns), with each column's fitted white-noise line dashed.
void plot_png(const std::string& png, const std::string& title,
              const std::vector<std::string>& names,
              const std::vector<std::vector<AllanPoint>>& curves,
              const std::vector<AllanFit>& fits) {
  const std::filesystem::path gnuplot = find_gnuplot();
  if (gnuplot.empty())
    throw std::runtime_error(
        "--png needs gnuplot, which is not on PATH (Debian: apt-get install gnuplot-nox)");

  std::string script;
  script += "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
            "  set terminal pngcairo size 1000,700 noenhanced\n"
            "} else {\n"
            "  set terminal png size 1000,700 noenhanced\n"
            "}\n";
  script += "set output " + gnuplot_quote(png) + "\n";
  script += "$adev << EOD\n";
  for (std::size_t r = 0; r < curves.front().size(); ++r) {
    script += fmt::format("{:.9g}", curves.front()[r].tau_s);
    for (const auto& c : curves) script += fmt::format(" {:.9g}", c[r].adev);
    script += "\n";
  }
  script += "EOD\n";
  std::vector<Kind> kinds;
  for (Kind k : {Kind::gyro, Kind::accel, Kind::other})
    for (const std::string& n : names)
      if (kind_of(n) == k) {
        kinds.push_back(k);
        break;
      }
  script += fmt::format("set multiplot layout {},1 title {}\n", kinds.size(), gnuplot_quote(title));
  script += "set logscale xy\nset grid xtics ytics mxtics mytics\nset format y '%.0e'\n"
            "set key outside right\nset xlabel 'tau [s]'\n";
  const double tau_lo = curves.front().front().tau_s, tau_hi = curves.front().back().tau_s;
  for (Kind k : kinds) {
    script += "set ylabel " + gnuplot_quote("Allan deviation [" + si_unit(k) + "]") + "\n";
    std::string plot = "plot";
    int style = 1;
    for (std::size_t c = 0; c < names.size(); ++c) {
      if (kind_of(names[c]) != k) continue;
      if (style > 1) plot += ",";
      plot += fmt::format(" $adev using 1:{} with linespoints pt 7 ps 0.5 lc {} title {}", c + 2,
                          style, gnuplot_quote(names[c]));
      if (fits[c].white_density > 0.0)
        plot += fmt::format(", [{:.9g}:{:.9g}] {:.9g}/sqrt(x) with lines dt 2 lc {} notitle",
                            tau_lo, tau_hi, fits[c].white_density, style);
      ++style;
    }
    script += plot + "\n";
  }
  script += "unset multiplot\nset output\n";

  const std::filesystem::path script_file =
      std::filesystem::temp_directory_path() /
      fmt::format("navemu-allan-{}-{}.gp", ::getpid(), script_counter++);
  {
    std::ofstream f(script_file);
    f << script;
    if (!f) throw std::runtime_error("cannot write the gnuplot script " + script_file.string());
  }
  std::string output;
  const int status = run_capturing({gnuplot.string(), script_file.string()}, output);
  std::error_code ec;
  std::filesystem::remove(script_file, ec);
  std::error_code size_ec;
  const bool written = std::filesystem::exists(png, size_ec) &&
                       std::filesystem::file_size(png, size_ec) > 0;
  if (status != 0 || !written) {
    for (char& ch : output)
      if (ch == '\n') ch = ' ';
    throw std::runtime_error(
        fmt::format("gnuplot could not write {}: {}", png, std::string(trim(output))));
  }
}

}  // namespace

std::shared_ptr<AllanOptions> add_allan_command(CLI::App& app) {
  auto opt = std::make_shared<AllanOptions>();
  CLI::App* cmd = app.add_subcommand(
      "allan", "Overlapping Allan deviation of IMU samples, with the fitted noise terms");
  cmd->footer(
      "Reads a CSV file with a header row (as written by navemu imu: time_s, f_x_mps2, f_y_mps2,\n"
      "f_z_mps2, w_x_radps, w_y_radps, w_z_radps, temperature_c) and computes the overlapping\n"
      "Allan deviation (IEEE Std 952-1997 Annex C) of each column at log-spaced tau.\n"
      "The sample rate comes from time_s (uniform steps required) unless --rate is given.\n"
      "Prints, per column, the white noise N (read at tau = 1 s on the -1/2 slope), the bias\n"
      "instability B (curve minimum / 0.664, and its tau) and the random walk K (+1/2 slope at\n"
      "tau = 3 s, '-' when the curve does not rise), in SI units and in datasheet units:\n"
      "gyro ARW deg/sqrt(h), bias instability deg/h, RRW deg/h/sqrt(h); accelerometer VRW\n"
      "m/s/sqrt(h), bias instability mg, AccRW m/s/h^1.5. Columns ending in _radps are\n"
      "gyroscopes, _mps2 accelerometers.\n"
      "--out writes the curves as CSV: tau_s, then one Allan deviation column per input column\n"
      "(in its unit); '--out -' writes them to stdout and the table to stderr.\n"
      "--png draws a log-log plot with gnuplot.\n"
      "Example:\n"
      "  navemu imu --profile bmi160 --duration 10800 --rate 200 --out static.csv\n"
      "  navemu allan static.csv --out adev.csv --png adev.png");
  cmd->add_option("FILE", opt->file, "IMU CSV file")->required();
  cmd->add_option("--columns", opt->columns,
                  "Comma-separated columns to analyse (default: the six sensor columns)")
      ->delimiter(',');
  cmd->add_option("--rate", opt->rate_hz, "Sample rate in Hz (default: from the time_s column)")
      ->check(positive_number());
  cmd->add_option("--points-per-decade", opt->points_per_decade, "Tau values per decade")
      ->capture_default_str()
      ->check(number_between(1, 100));
  cmd->add_option("--png", opt->png_file, "Write a log-log plot of the curves to this PNG file");
  cmd->add_option("--out", opt->out_file,
                  "Write the curves to this CSV file ('-': standard output)");
  return opt;
}

int run_allan(const AllanOptions& opt, std::ostream& out, std::ostream& err) {
  std::vector<std::string> names = opt.columns;
  if (names.empty()) names.assign(kSensorColumns.begin(), kSensorColumns.end());
  const bool rate_from_time = !opt.rate_hz.has_value();
  Table table = read_columns(opt.file, names, rate_from_time);
  const double dt = rate_from_time ? sampling_interval(opt.file, table) : 1.0 / *opt.rate_hz;
  const std::size_t rows = table.lines.size();
  table.time_s = {};
  table.lines = {};

  std::vector<std::vector<AllanPoint>> curves;
  std::vector<AllanFit> fits;
  for (std::vector<double>& column : table.data) {
    curves.push_back(overlapping_allan_deviation(column, dt, opt.points_per_decade));
    column = {};
    fits.push_back(fit_allan(curves.back()));
  }

  std::ostream& report = opt.out_file == "-" ? err : out;
  if (opt.out_file == "-") {
    write_csv(out, names, curves);
  } else if (!opt.out_file.empty()) {
    std::ofstream f(opt.out_file);
    if (!f) throw InputError(opt.out_file, 0, "--out", "cannot create the file");
    write_csv(f, names, curves);
    if (!f) throw InputError(opt.out_file, 0, "--out", "cannot write the file");
  }
  fmt::print(report, "{}: {} samples at {:.6g} Hz ({:.6g} s), tau {:.6g} s to {:.6g} s\n",
             opt.file, rows, 1.0 / dt, static_cast<double>(rows) * dt, curves.front().front().tau_s,
             curves.front().back().tau_s);
  print_fits(report, names, fits);
  if (!opt.png_file.empty()) {
    plot_png(opt.png_file, std::filesystem::path(opt.file).filename().string(), names, curves,
             fits);
    fmt::print(report, "plot: {}\n", opt.png_file);
  }
  return 0;
}

}  // namespace navemu
