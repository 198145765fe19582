// IMU profiles (emulator/imu_profile.hpp): every shipped profile loads; units convert once; bad
// files give "<file>:<line>: <key>: <problem>". And `navemu imu` run in-process.

#include "emulator/imu_profile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "emulator/cli.hpp"
#include "tests/emulator/cli_runner.hpp"
#include "tests/test_support.hpp"
#include "core/errors.hpp"

namespace navemu {
namespace {

using test::CliRun;
using test::navemu;

constexpr double kPi = 3.14159265358979323846;

std::filesystem::path write_temp(const std::string& name, const std::string& content) {
  const auto p = std::filesystem::path(::testing::TempDir()) / name;
  std::ofstream(p) << content;
  return p;
}

// The message of the InputError that loading `content` raises ("" when none).
std::string load_error(const std::string& name, const std::string& content) {
  const auto file = write_temp(name, content);
  try {
    load_imu_profile_file(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::path(::testing::TempDir()) / name).string();
}

const std::string kMinimal =
    "model: datasheet\n"                              // 1
    "output_rate_hz: 100\n"                           // 2
    "accel_white_density_mps2_per_rthz: 1e-3\n"       // 3
    "gyro_white_density_radps_per_rthz: 1e-4\n";      // 4

TEST(ImuProfile, EveryShippedProfileLoadsAndRuns) {
  const auto names = available_imu_profiles();
  for (const char* expected : {"paper_phidget", "paper_fig2_gyro", "bmi160", "adis16448",
                               "xsens_mti100", "microstrain_gx4", "tactical"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  for (const std::string& n : names) {
    const ImuProfile prof = load_imu_profile(n);
    EXPECT_EQ(prof.name, n);
    const ImuParams p = imu_params_for_run(prof, 600.0);
    EXPECT_GT(p.accel.white_density, 0.0) << n;
    EXPECT_GT(p.gyro.white_density, 0.0) << n;
    ImuModel m(p, 1);  // validates the parameters
    ImuSample s;
    EXPECT_TRUE(m.step(GpsTime{0}, IdealImu{}, p.reference_temperature_c, s)) << n;
  }
}

TEST(ImuProfile, UnitsConvertedToSi) {
  const ImuParams t = load_imu_profile("tactical").params;
  EXPECT_NEAR(t.gyro.white_density, 0.09 * kPi / 180.0 / 60.0, 1e-15);  // deg/sqrt(h)
  EXPECT_NEAR(t.gyro.bias_instability, 1.0 * kPi / 180.0 / 3600.0, 1e-15);  // deg/h
  EXPECT_NEAR(t.accel.white_density, 0.06 / 60.0, 1e-15);                  // m/s/sqrt(h)
  EXPECT_NEAR(t.accel.bias_instability, 0.05e-3 * 9.80665, 1e-15);         // mg
  EXPECT_NEAR(t.gyro.full_scale, 1000.0 * kPi / 180.0, 1e-12);
  const ImuProfile fig2 = load_imu_profile("paper_fig2_gyro");
  EXPECT_EQ(fig2.model, "paper");
  EXPECT_NEAR(fig2.paper.gyro_null_offset.x(), 3.0 * kPi / 180.0 / 3600.0, 1e-15);
  // A paper profile's quantization term uses the run's duration unless the file fixes it.
  EXPECT_GT(imu_params_for_run(fig2, 60.0).gyro.white_density,
            imu_params_for_run(fig2, 1200.0).gyro.white_density);
  // By path as well as by name.
  const auto file = write_temp("minimal.yaml", kMinimal);
  const ImuProfile by_path = load_imu_profile(file.string());
  EXPECT_EQ(by_path.name, "minimal");
  EXPECT_EQ(by_path.params.internal_rate_hz, 100.0);
}

TEST(ImuProfile, RateOverride) {
  const ImuProfile prof = load_imu_profile("bmi160");  // 1600 Hz internal, 200 Hz output
  const ImuParams p = imu_params_for_run(prof, 10.0, 100.0);
  EXPECT_EQ(p.output_rate_hz, 100.0);
  EXPECT_EQ(p.internal_rate_hz, 1600.0);
  const ImuParams q = imu_params_for_run(prof, 10.0, 300.0);
  EXPECT_EQ(q.internal_rate_hz, 1800.0);
}

TEST(ImuProfile, BadInputNamesFileLineAndKey) {
  auto expect_error = [](const std::string& name, const std::string& content,
                         const std::string& expected_tail) {
    const std::string msg = load_error(name, content);
    EXPECT_EQ(msg, temp_path(name) + ":" + expected_tail) << name;
  };
  expect_error("unknown_key.yaml", kMinimal + "bogus_key: 1\n",
               "5: bogus_key: unknown key for a 'datasheet' profile");
  expect_error("unknown_unit.yaml", kMinimal + "gyro_bias_instability_furlongs: 1\n",
               "5: gyro_bias_instability_furlongs: unknown unit; use one of "
               "gyro_bias_instability_radps, gyro_bias_instability_dps, "
               "gyro_bias_instability_degph");
  expect_error("missing.yaml",
               "model: datasheet\noutput_rate_hz: 100\naccel_white_density_mps2_per_rthz: 1e-3\n",
               "1: gyro_white_density_radps_per_rthz: missing required key");
  expect_error("negative_tau.yaml", kMinimal + "accel_bias_instability_tau_s: -5\n",
               "5: accel_bias_instability_tau_s: must be positive (got -5)");
  expect_error("negative_sigma.yaml", kMinimal + "gyro_bias_instability_degph: -2\n",
               "5: gyro_bias_instability_degph: must not be negative (got -2)");
  expect_error("non_numeric.yaml", kMinimal + "accel_random_walk_mps3_per_rthz: abc\n",
               "5: accel_random_walk_mps3_per_rthz: 'abc' is not a number");
  expect_error("nan.yaml", kMinimal + "latency_s: .nan\n", "5: latency_s: '.nan' is not finite");
  expect_error("twice.yaml", kMinimal + "gyro_white_density_deg_per_rth: 0.1\n",
               "5: gyro_white_density_deg_per_rth: given twice (in different units)");
  expect_error("vector.yaml", kMinimal + "gyro_null_offset_degph: [1, 2]\n",
               "5: gyro_null_offset_degph: expected [x, y, z]");
  expect_error("model.yaml", "model: magic\noutput_rate_hz: 100\n",
               "1: model: must be 'datasheet' or 'paper'");
  expect_error("no_model.yaml", "output_rate_hz: 100\n",
               "1: model: missing required key (datasheet or paper)");
  expect_error("rates.yaml", kMinimal + "internal_rate_hz: 250\n",
               "5: internal_rate_hz: must be a whole multiple of output_rate_hz");
  expect_error("paper_key.yaml", kMinimal + "quality_factor: 0.2\n",
               "5: quality_factor: unknown key for a 'datasheet' profile");
  expect_error("paper_missing.yaml",
               "model: paper\noutput_rate_hz: 125\nquality_factor: 0.2\n"
               "gm_correlation_time_s: 10\naccel_white_noise_mps2: 0.12\n",
               "1: gyro_white_noise_dps: missing required key");
  expect_error("syntax.yaml", "model: datasheet\noutput_rate_hz: [100\n",
               "3: YAML syntax error: end of sequence flow not found");
}

TEST(ImuProfile, UnknownProfileListsAvailable) {
  try {
    load_imu_profile("no_such_imu");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("--profile: unknown IMU profile 'no_such_imu' (available: "),
              std::string::npos)
        << msg;
    EXPECT_NE(msg.find("bmi160"), std::string::npos);
  }
}

// The columns of navemu imu's CSV, found by name in its header, in this order in each row.
enum Col : std::size_t { kT, kFx, kFy, kFz, kWx, kWy, kWz, kTemp, kColumns };
constexpr const char* kColumnNames[kColumns] = {"time_s",    "f_x_mps2",  "f_y_mps2",  "f_z_mps2",
                                                "w_x_radps", "w_y_radps", "w_z_radps", "temperature_c"};

std::vector<std::vector<double>> read_rows(const std::string& path, std::string& header) {
  std::ifstream(path) >> header;
  const test::CsvTable t(path);
  std::vector<std::vector<double>> rows(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_EQ(t.row(i).size(), t.header().size()) << "row " << i;
    for (const char* name : kColumnNames) rows[i].push_back(t.num(i, name));
  }
  return rows;
}

TEST(ImuCli, WritesOneRowPerOutputSample) {
  const std::string out = temp_path("xsens.csv");
  const CliRun r = navemu({"imu", "--profile", "xsens_mti100", "--duration", "2", "--out", out});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("200 samples written"), std::string::npos) << r.err;
  std::string header;
  const auto rows = read_rows(out, header);
  EXPECT_EQ(header, "time_s,f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_y_radps,w_z_radps,temperature_c");
  ASSERT_EQ(rows.size(), 200u);
  EXPECT_DOUBLE_EQ(rows[0][kT], 0.002);  // the profile's 2 ms latency
  EXPECT_DOUBLE_EQ(rows[1][kT], 0.012);
  EXPECT_DOUBLE_EQ(rows[199][kT], 1.992);
  for (const auto& row : rows) ASSERT_EQ(row.size(), static_cast<std::size_t>(kColumns));
  // --rate overrides the output rate.
  const CliRun fast =
      navemu({"imu", "--profile", "xsens_mti100", "--duration", "2", "--rate", "200", "--out", out});
  ASSERT_EQ(fast.code, 0) << fast.err;
  EXPECT_EQ(read_rows(out, header).size(), 400u);
}

TEST(ImuCli, SameSeedByteIdenticalOtherSeedDifferent) {
  const std::string a = temp_path("a.csv"), b = temp_path("b.csv"), c = temp_path("c.csv");
  for (const auto& [file, seed] : {std::pair{a, "5"}, std::pair{b, "5"}, std::pair{c, "6"}}) {
    const CliRun r = navemu({"imu", "--profile", "paper_phidget", "--duration", "5", "--seed", seed,
                             "--out", file});
    ASSERT_EQ(r.code, 0) << r.err;
  }
  EXPECT_EQ(test::read_file(a), test::read_file(b));
  EXPECT_NE(test::read_file(a), test::read_file(c));
}

// A static, level, north-facing IMU with white noise only: mean specific force (0, 0, -g) and
// mean rate the Earth rate projected on the body axes (W cos(lat), 0, -W sin(lat)).
TEST(ImuCli, StaticLevelImuSensesGravityAndEarthRate) {
  const auto profile = write_temp("white_only.yaml",
                                  "model: datasheet\n"
                                  "output_rate_hz: 100\n"
                                  "internal_rate_hz: 400\n"
                                  "bandwidth_hz: 40\n"
                                  "accel_white_density_mps2_per_rthz: 1e-3\n"
                                  "gyro_white_density_radps_per_rthz: 1e-5\n");
  const std::string out = temp_path("static.csv");
  const CliRun r = navemu({"imu", "--profile", profile.string(), "--duration", "600", "--at",
                           "32.3,-90.9,60", "--seed", "3", "--out", out});
  ASSERT_EQ(r.code, 0) << r.err;
  std::string header;
  const auto rows = read_rows(out, header);
  ASSERT_EQ(rows.size(), 60000u);
  std::vector<double> mean(kColumns, 0.0);
  for (const auto& row : rows)
    for (std::size_t i = 0; i < kColumns; ++i) mean[i] += row[i] / static_cast<double>(rows.size());
  // Standard error of a 600-s mean of white noise: density / sqrt(600 s); bound 5 of them.
  const double se_f = 5.0 * 1e-3 / std::sqrt(600.0), se_w = 5.0 * 1e-5 / std::sqrt(600.0);
  const double lat = 32.3 * kPi / 180.0, we = 7.292115e-5;
  // Normal gravity at 32.3 deg, 60 m (Somigliana with the free-air gradient): 9.7949 m/s^2.
  EXPECT_NEAR(mean[kFx], 0.0, se_f + 1e-4);  // + the ~1e-5 north component of normal gravity
  EXPECT_NEAR(mean[kFy], 0.0, se_f);
  EXPECT_NEAR(mean[kFz], -9.7949, se_f + 2e-4);
  EXPECT_NEAR(mean[kWx], we * std::cos(lat), se_w);
  EXPECT_NEAR(mean[kWy], 0.0, se_w);
  EXPECT_NEAR(mean[kWz], -we * std::sin(lat), se_w);
  EXPECT_NEAR(mean[kTemp], 25.0, 1e-9);
}

// A profile with every error term zero: the output is the ideal IMU.
const std::string kIdeal =
    "model: datasheet\n"
    "output_rate_hz: 100\n"
    "internal_rate_hz: 200\n"
    "accel_white_density_mps2_per_rthz: 0\n"
    "gyro_white_density_radps_per_rthz: 0\n";

const std::string kCircle = std::string(NAVEMU_SOURCE_DIR) + "/configs/truth/circle_paper.csv";

// The paper's circle (configs/truth/circle_paper.csv: 9.144 m radius, 2 m/s, clockwise seen
// from above, level, at 32.3 N) through an ideal IMU, over exactly its 8 loops: in FRD the
// centripetal specific force is +v^2/r on y (less the Coriolis term 2 W sin(lat) v of the
// Earth's rotation) and the yaw rate +v/r on z (plus the Earth rate's down component
// -W sin(lat)); the horizontal Earth rate and transport-rate terms average out over whole loops
// except the pitch rate -v/R of moving over the curved Earth.
TEST(ImuCli, TruthCircleSensesCentripetalForceAndTurnRate) {
  const auto profile = write_temp("ideal.yaml", kIdeal);
  const double r = 9.144, v = 2.0, lat = 32.3 * kPi / 180.0, we = 7.2921151467e-5;
  const double loops_s = 8.0 * 2.0 * kPi * r / v;
  const std::string out = temp_path("circle.csv");
  const CliRun run = navemu({"imu", "--profile", profile.string(), "--truth", kCircle,
                             "--duration", std::to_string(loops_s), "--out", out});
  ASSERT_EQ(run.code, 0) << run.err;
  std::string header;
  const auto rows = read_rows(out, header);
  // Internal instants n = 0 .. round(200 loops_s) - 1, every second one output.
  ASSERT_EQ(rows.size(), static_cast<std::size_t>((std::llround(loops_s * 200.0) + 1) / 2));
  std::vector<double> mean(kColumns, 0.0);
  for (const auto& row : rows)
    for (std::size_t i = 0; i < kColumns; ++i) mean[i] += row[i] / static_cast<double>(rows.size());
  EXPECT_NEAR(mean[kFy], v * v / r, 1e-3);
  EXPECT_NEAR(mean[kFy], v * v / r - 2.0 * we * std::sin(lat) * v, 1e-5);
  EXPECT_NEAR(mean[kFx], 0.0, 1e-5);
  EXPECT_NEAR(mean[kFz], -9.7949, 2e-4);
  EXPECT_NEAR(mean[kWz], v / r - we * std::sin(lat), 1e-6);
  EXPECT_NEAR(mean[kWy], -v / 6.372e6, 1e-8);  // -v / R: pitching over the curved Earth
  EXPECT_NEAR(mean[kWx], 0.0, 1e-7);
  EXPECT_NEAR(mean[kTemp], 25.0, 1e-9);
  // Every sample, not only the mean: a constant-speed circle is sensed as constant.
  for (const auto& row : rows) {
    ASSERT_NEAR(row[kFy], mean[kFy], 2e-4);
    ASSERT_NEAR(row[kWz], mean[kWz], 1e-6);
  }
}

TEST(ImuCli, TruthFileSameSeedByteIdentical) {
  const std::string a = temp_path("ta.csv"), b = temp_path("tb.csv"), c = temp_path("tc.csv");
  for (const auto& [file, seed] : {std::pair{a, "5"}, std::pair{b, "5"}, std::pair{c, "6"}}) {
    const CliRun r = navemu({"imu", "--profile", "bmi160", "--truth", kCircle, "--duration", "20",
                             "--seed", seed, "--out", file});
    ASSERT_EQ(r.code, 0) << r.err;
  }
  EXPECT_EQ(test::read_file(a), test::read_file(b));
  EXPECT_NE(test::read_file(a), test::read_file(c));
  std::string header;
  EXPECT_EQ(read_rows(a, header).size(), 4000u);  // 20 s at bmi160's 200 Hz
}

TEST(ImuCli, TruthFileSpanAndDuration) {
  const auto profile = write_temp("ideal_span.yaml", kIdeal);
  const std::string out = temp_path("span.csv");
  // Without --duration: the file's span, 229.9 s.
  const CliRun all =
      navemu({"imu", "--profile", profile.string(), "--truth", kCircle, "--out", out});
  ASSERT_EQ(all.code, 0) << all.err;
  std::string header;
  const auto rows = read_rows(out, header);
  ASSERT_EQ(rows.size(), 22990u);
  EXPECT_DOUBLE_EQ(rows.front()[kT], 0.0);
  EXPECT_DOUBLE_EQ(rows.back()[kT], 229.89);
  // Longer than the span: an error.
  const CliRun longer = navemu({"imu", "--profile", profile.string(), "--truth", kCircle,
                                "--duration", "300", "--out", out});
  EXPECT_EQ(longer.code, 1);
  EXPECT_EQ(longer.err,
            "navemu: --duration: 300 s is longer than the truth file's span (229.9 s, 0 to "
            "229.9 s)\n");
  // The static truth still needs --duration.
  const CliRun none = navemu({"imu", "--profile", profile.string(), "--out", out});
  EXPECT_EQ(none.code, 1);
  EXPECT_EQ(none.err, "navemu: --duration: required with --truth static\n");
  // A bad truth file: its error, before any output.
  const auto bad = write_temp("bad_truth.csv",
                              "time_s,lat_deg,lon_deg,h_m,v_n_mps,v_e_mps,v_d_mps,roll_deg,"
                              "pitch_deg,yaw_deg\n0,32,-90,0,0,0,0,0,0,0\n1,32,-90,0,0,0,0,0,0,0\n"
                              "2,32,-90,0,0,0,0,0,x,0\n");
  const CliRun badrun =
      navemu({"imu", "--profile", profile.string(), "--truth", bad.string(), "--out", out});
  EXPECT_EQ(badrun.code, 1);
  EXPECT_EQ(badrun.err,
            "navemu: " + bad.string() + ":4: pitch_deg: not a number: 'x'\n");
}

// With f/w columns the simulator's own values are the ideal output (linear in between), and
// temperature_c drives the sample's temperature.
TEST(ImuCli, TruthFileRatesAndTemperaturePassThrough) {
  const auto profile = write_temp("ideal_rates.yaml", kIdeal);
  const auto truth = write_temp(
      "rates_truth.csv",
      "time_s,lat_deg,lon_deg,h_m,v_n_mps,v_e_mps,v_d_mps,roll_deg,pitch_deg,yaw_deg,"
      "f_x_mps2,f_y_mps2,f_z_mps2,w_x_radps,w_y_radps,w_z_radps,temperature_c\n"
      "100,32,-90,0,0,0,0,0,0,0,1,2,-9,0.1,0.2,0.3,20\n"
      "101,32,-90,0,0,0,0,0,0,0,3,2,-9,0.1,0.2,0.5,30\n"
      "102,32,-90,0,0,0,0,0,0,0,3,2,-9,0.1,0.2,0.5,30\n");
  const std::string out = temp_path("rates_out.csv");
  const CliRun r =
      navemu({"imu", "--profile", profile.string(), "--truth", truth.string(), "--out", out});
  ASSERT_EQ(r.code, 0) << r.err;
  std::string header;
  const auto rows = read_rows(out, header);
  ASSERT_EQ(rows.size(), 200u);
  EXPECT_DOUBLE_EQ(rows[0][kT], 100.0);  // the file's time base
  EXPECT_NEAR(rows[50][kT], 100.5, 1e-9);
  EXPECT_NEAR(rows[50][kFx], 2.0, 1e-9);
  EXPECT_NEAR(rows[50][kWz], 0.4, 1e-9);
  EXPECT_NEAR(rows[50][kTemp], 25.0, 1e-9);
  EXPECT_NEAR(rows[150][kFx], 3.0, 1e-9);
}

TEST(ImuCli, BadInputGivesOneLineError) {
  const std::string out = temp_path("bad.csv");
  const CliRun unknown = navemu({"imu", "--profile", "nope", "--duration", "1", "--out", out});
  EXPECT_EQ(unknown.code, 1);
  EXPECT_NE(unknown.err.find("available: "), std::string::npos) << unknown.err;
  EXPECT_EQ(std::count(unknown.err.begin(), unknown.err.end(), '\n'), 1);
  const CliRun negative = navemu({"imu", "--profile", "bmi160", "--duration", "-3", "--out", out});
  EXPECT_EQ(negative.code, 1);
  EXPECT_EQ(negative.err, "navemu: --duration: must be positive (got -3)\n");
  const CliRun truth =
      navemu({"imu", "--profile", "bmi160", "--duration", "1", "--truth", "x.csv", "--out", out});
  EXPECT_EQ(truth.code, 1);
  const CliRun at = navemu(
      {"imu", "--profile", "bmi160", "--duration", "1", "--at", "95,0,0", "--out", out});
  EXPECT_EQ(at.code, 1);
  const auto bad = write_temp("bad_profile.yaml", kMinimal + "gyro_bias_instability_tau_s: 0\n");
  const CliRun file = navemu({"imu", "--profile", bad.string(), "--duration", "1", "--out", out});
  EXPECT_EQ(file.code, 1);
  EXPECT_EQ(file.err, "navemu: " + bad.string() +
                          ":5: gyro_bias_instability_tau_s: must be positive (got 0)\n");
  const CliRun missing = navemu({"imu", "--profile", "bmi160", "--duration", "1"});
  EXPECT_EQ(missing.code, 2);
}

}  // namespace
}  // namespace navemu
