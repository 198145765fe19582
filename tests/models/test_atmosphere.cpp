#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "models/atmosphere.hpp"
#include "protocols/rinex.hpp"
#include "tests/rinex_data.hpp"
#include "tests/spirent_log.hpp"
#include "tests/test_support.hpp"

namespace navemu {
namespace {

constexpr double kC = kSpeedOfLight_mps;

// ---------------------------------------------------------------------------------------
// Reference data: the Spirent SimGEN static scenario (../shared/data/README.md, 1c), its
// truth log read by tests/spirent_log.hpp (every constellation's rows).
// Receiver at 30 N, 95 E, 0 m (a simulator input, exact).

using test::kSpirentRx;
using test::SpirentRow;

// GPSA / GPSB lines of the RINEX 3.04 nav header the scenario used (format A4,1X,4D12.4).
KlobucharCoefficients read_spirent_klobuchar() {
  const auto path =
      test::shared_data("gnss/spirent_simgen_static_20230108/Spirent_RINEX_GN.23N");
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  KlobucharCoefficients k;
  int found = 0;
  std::string line;
  while (std::getline(in, line) && line.find("END OF HEADER") == std::string::npos) {
    const bool a = line.rfind("GPSA", 0) == 0;
    const bool b = line.rfind("GPSB", 0) == 0;
    if (!a && !b) continue;
    for (std::size_t i = 0; i < 4; ++i) {
      std::string field = line.substr(5 + 12 * i, 12);
      std::replace(field.begin(), field.end(), 'D', 'E');
      (a ? k.alpha : k.beta)[i] = std::stod(field);
    }
    ++found;
  }
  EXPECT_EQ(found, 2) << "GPSA/GPSB header lines";
  return k;
}

// ---------------------------------------------------------------------------------------
// Klobuchar (IS-GPS-200 20.3.3.5.2.5, Figure 20-4)

TEST(Klobuchar, NightTimeIsConstantTimesObliquity) {
  // At local midnight |x| >= 1.57, so T = F * 5 ns with F = 1 + 16 (0.53 - E)^3.
  KlobucharCoefficients k;
  k.alpha = {1e-8, 0.0, 0.0, 0.0};
  k.beta = {72000.0, 0.0, 0.0, 0.0};
  const Geodetic rx{0.0, 0.0, 0.0};
  // Zenith: psi = 0.0137/0.61 - 0.022, pierce point at the user; GPS time of day 0 -> t = 0.
  const AzEl zenith{0.0, kPi / 2.0};
  const double f_zenith = 1.0 + 16.0 * std::pow(0.53 - 0.5, 3);
  EXPECT_NEAR(klobuchar_delay_l1_s(k, rx, zenith, GpsTime{0}), f_zenith * 5e-9, 1e-20);
  // Same instant a week later (the model only sees the time of day).
  const GpsTime next_week{kSecondsPerWeek * kNsPerS};
  EXPECT_NEAR(klobuchar_delay_l1_s(k, rx, zenith, next_week), f_zenith * 5e-9, 1e-20);
}

TEST(Klobuchar, PeakAtLocalAfternoonWithAmplitudeFloorAndPeriodFloor) {
  // alpha = (10 ns, 0, 0, 0): AMP = 10 ns everywhere; beta all 0 -> PER floor 72000 s.
  // User on the equator at longitude 0, zenith: pierce point at the user, lambda_i = 0,
  // so local time = GPS time of day. At 14:00 (50400 s) x = 0 and T = F (5 ns + AMP).
  KlobucharCoefficients k;
  k.alpha = {10e-9, 0.0, 0.0, 0.0};
  const Geodetic rx{0.0, 0.0, 0.0};
  const AzEl zenith{0.0, kPi / 2.0};
  const double f = 1.0 + 16.0 * std::pow(0.03, 3);
  const GpsTime t1400{50400 * kNsPerS};
  EXPECT_NEAR(klobuchar_delay_l1_s(k, rx, zenith, t1400), f * 15e-9, 1e-20);
  // Two hours later: x = 2 pi 7200 / 72000 (period floor), series 1 - x^2/2 + x^4/24.
  const double x = 2.0 * kPi * 7200.0 / 72000.0;
  const double series = 1.0 - x * x / 2.0 + std::pow(x, 4) / 24.0;
  EXPECT_NEAR(klobuchar_delay_l1_s(k, rx, zenith, GpsTime{57600 * kNsPerS}),
              f * (5e-9 + 10e-9 * series), 1e-20);
  // A negative amplitude is floored to zero: only the 5 ns night-time term remains.
  k.alpha = {-10e-9, 0.0, 0.0, 0.0};
  EXPECT_NEAR(klobuchar_delay_l1_s(k, rx, zenith, t1400), f * 5e-9, 1e-20);
}

TEST(Klobuchar, PiercePointLatitudeIsClampedAndLocalTimeWraps) {
  // Near the pole looking north at low elevation, phi_u + psi cos A exceeds 0.416 and is
  // clamped; near the date line the local time wraps into [0, 86400). Both must give finite,
  // positive delays that do not depend on how far past the clamp the pierce point would be.
  KlobucharCoefficients k;
  k.alpha = {1e-8, 1e-8, -6e-8, 6e-8};
  k.beta = {9e4, 0.0, -2e5, 1e5};
  const AzEl north_low{0.0, 10.0 * kDegToRad};
  const double d80 = klobuchar_delay_l1_s(k, {80.0, 10.0, 0.0}, north_low, GpsTime{0});
  const double d85 = klobuchar_delay_l1_s(k, {85.0, 10.0, 0.0}, north_low, GpsTime{0});
  EXPECT_GT(d80, 0.0);
  EXPECT_GT(d85, 0.0);
  // phi_i clamped to 0.416 in both cases; lambda_i differs only through sin(A) = 0, so equal.
  EXPECT_DOUBLE_EQ(d80, d85);
  const double east = klobuchar_delay_l1_s(k, {0.0, 179.9, 0.0}, {kPi / 2.0, 0.3}, GpsTime{0});
  EXPECT_TRUE(std::isfinite(east));
  EXPECT_GT(east, 0.0);
}

TEST(Klobuchar, ZeroBelowHorizon) {
  KlobucharCoefficients k;
  k.alpha = {1e-8, 0.0, 0.0, 0.0};
  EXPECT_EQ(klobuchar_delay_l1_s(k, {}, {0.0, 0.0}, GpsTime{0}), 0.0);
  EXPECT_EQ(klobuchar_delay_l1_s(k, {}, {0.0, -0.1}, GpsTime{0}), 0.0);
}

// Every GPS row of the Spirent SimGEN log (465 rows, 10:00-14:00 GPST every 5 min) against
// the simulator's own Klobuchar delay on L1 (Iono_delay Group A, seconds). The log's
// azimuth is in (-pi, pi]; it is brought into [0, 2pi) as AzEl documents (cos/sin are
// unaffected). The log rounds elevation to 1e-4 rad, which alone moves the delay by up to
// ~1 mm at the lowest elevations.
TEST(KlobucharSpirent, MatchesSimulatorLogWithinFiveMillimetres) {
  NAVEMU_REQUIRE_SHARED();
  // Coefficients through the RINEX reader, cross-checked against the raw header lines.
  const NavData nav = test::rinex_nav_file(
      test::shared_data("gnss/spirent_simgen_static_20230108/Spirent_RINEX_GN.23N"));
  ASSERT_TRUE(nav.klobuchar.has_value());
  const KlobucharCoefficients k = *nav.klobuchar;
  const KlobucharCoefficients raw = read_spirent_klobuchar();
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(k.alpha[i], raw.alpha[i]);
    EXPECT_DOUBLE_EQ(k.beta[i], raw.beta[i]);
  }
  EXPECT_DOUBLE_EQ(k.alpha[0], 2.4214e-08);
  EXPECT_DOUBLE_EQ(k.beta[3], 2.6214e+05);
  const auto rows = test::read_spirent_rows();
  int n = 0;
  double max_err_s = 0.0;
  SpirentRow worst;
  for (const auto& r : rows) {
    if (r.system != "GPS") continue;
    ++n;
    AzEl dir{r.az_rad < 0.0 ? r.az_rad + 2.0 * kPi : r.az_rad, r.el_rad};
    const double d = klobuchar_delay_l1_s(k, kSpirentRx, dir, r.t_receive);
    const double err = std::abs(d - r.iono_l1_s);
    if (err > max_err_s) {
      max_err_s = err;
      worst = r;
    }
    EXPECT_LT(err, 5e-3 / kC) << "PRN " << r.prn << " t " << r.t_receive.ns << " el " << r.el_rad;
  }
  EXPECT_EQ(n, 465);
  std::printf("[ Klobuchar vs SimGEN ] %d GPS rows, max |error| = %.3e s = %.2f mm "
              "(PRN %d, el %.4f rad)\n",
              n, max_err_s, max_err_s * kC * 1e3, worst.prn, worst.el_rad);
}

// ---------------------------------------------------------------------------------------
// Standard atmosphere and Saastamoinen (RTKLIB tropmodel form)

TEST(AtmosphereStandard, SeaLevelAndLapse) {
  const Meteo m0 = standard_atmosphere(0.0, 0.5);
  EXPECT_DOUBLE_EQ(m0.pressure_hpa, 1013.25);
  EXPECT_DOUBLE_EQ(m0.temperature_k, 288.16);  // 15 degC + 273.16, as RTKLIB
  EXPECT_DOUBLE_EQ(m0.relative_humidity, 0.5);
  // 1000 m: 1013.25 (1 - 0.022557)^5.2568 = 898.730 hPa; 15 - 6.5 = 8.5 degC.
  const Meteo m1 = standard_atmosphere(1000.0);
  EXPECT_NEAR(m1.pressure_hpa, 898.730, 0.001);
  EXPECT_NEAR(m1.temperature_k, 281.66, 1e-9);
  EXPECT_DOUBLE_EQ(m1.relative_humidity, 0.7);  // default
  // Below the ellipsoid: taken as 0 m.
  const Meteo mneg = standard_atmosphere(-50.0);
  EXPECT_DOUBLE_EQ(mneg.pressure_hpa, 1013.25);
  EXPECT_DOUBLE_EQ(mneg.temperature_k, 288.16);
}

// Davis et al. (1985) zenith hydrostatic delay 0.0022768 P / (1 - 0.00266 cos 2phi -
// 0.00028 H_km): at sea level, P = 1013.25 hPa, phi = 45 deg, cos 90 deg = 0 and
// ZHD = 0.0022768 * 1013.25 = 2.30697 m, i.e. 2.3070 m.
TEST(Saastamoinen, DavisZenithHydrostaticAtFortyFiveDegrees) {
  const Meteo m = standard_atmosphere(0.0, 0.0);
  const TropoDelay d = saastamoinen_delay({45.0, 0.0, 0.0}, kPi / 2.0, m);
  EXPECT_NEAR(d.hydrostatic_m, 2.3070, 5e-5);
  EXPECT_DOUBLE_EQ(d.wet_m, 0.0);
  EXPECT_DOUBLE_EQ(d.total_m(), d.hydrostatic_m);
}

// Zenith wet delay by hand at 15 degC, RH 0.7: T = 288.16 K,
// e = 6.108 * 0.7 * exp((17.15 * 288.16 - 4684) / (288.16 - 38.45)) = 12.0119 hPa,
// ZWD = 0.002277 * (1255 / 288.16 + 0.05) * e = 0.12049 m.
TEST(Saastamoinen, ZenithWetByHand) {
  const TropoDelay d = saastamoinen_delay({0.0, 0.0, 0.0}, kPi / 2.0, standard_atmosphere(0.0));
  EXPECT_NEAR(d.wet_m, 0.12049, 5e-5);
  // Equator: 1 - 0.00266 cos 0 = 0.99734 -> ZHD = 2.30697 / 0.99734 = 2.31312 m.
  EXPECT_NEAR(d.hydrostatic_m, 2.31312, 5e-5);
}

TEST(Saastamoinen, SlantScalesAsOneOverCosZenith) {
  const Meteo m = standard_atmosphere(0.0, 0.6);
  const Geodetic rx{30.0, 95.0, 0.0};
  const TropoDelay zen = saastamoinen_delay(rx, kPi / 2.0, m);
  const TropoDelay at30 = saastamoinen_delay(rx, 30.0 * kDegToRad, m);
  EXPECT_NEAR(at30.hydrostatic_m, 2.0 * zen.hydrostatic_m, 1e-12);
  EXPECT_NEAR(at30.wet_m, 2.0 * zen.wet_m, 1e-12);
}

TEST(Saastamoinen, RtklibDomain) {
  const Meteo m = standard_atmosphere(0.0);
  // At or below the horizon, and outside [-100 m, 10 km]: no delay.
  EXPECT_EQ(saastamoinen_delay({0.0, 0.0, 0.0}, 0.0, m).total_m(), 0.0);
  EXPECT_EQ(saastamoinen_delay({0.0, 0.0, 0.0}, -0.1, m).total_m(), 0.0);
  EXPECT_EQ(saastamoinen_delay({0.0, 0.0, -150.0}, 1.0, m).total_m(), 0.0);
  EXPECT_EQ(saastamoinen_delay({0.0, 0.0, 10001.0}, 1.0, m).total_m(), 0.0);
  // Slightly below the ellipsoid: same as at 0 m.
  EXPECT_DOUBLE_EQ(saastamoinen_delay({0.0, 0.0, -50.0}, 1.0, m).hydrostatic_m,
                   saastamoinen_delay({0.0, 0.0, 0.0}, 1.0, m).hydrostatic_m);
  // Higher up: less delay.
  const double h2000 =
      saastamoinen_delay({0.0, 0.0, 2000.0}, 1.0, standard_atmosphere(2000.0)).total_m();
  EXPECT_LT(h2000, saastamoinen_delay({0.0, 0.0, 0.0}, 1.0, m).total_m() * 0.85);
}

// The SimGEN log's Tropo_delay (seconds) against saastamoinen_delay with
// standard_atmosphere(0, RH). SimGEN maps with Niell rather than 1/cos z, so only elevations
// from 30 deg up are compared. The wet delay is linear in RH, so RH is fitted in closed form
// (least squares over those rows); it comes out at 0.77.
TEST(TropoSpirent, MatchesSimulatorLogAboveThirtyDegrees) {
  NAVEMU_REQUIRE_SHARED();
  const auto rows = test::read_spirent_rows();
  const double min_el = 30.0 * kDegToRad;

  // total(RH) = hydro + RH * wet1: least squares for RH.
  double num = 0.0, den = 0.0;
  for (const auto& r : rows) {
    if (r.el_rad < min_el) continue;
    const double hyd = saastamoinen_delay(kSpirentRx, r.el_rad, standard_atmosphere(0.0, 0.0))
                           .hydrostatic_m;
    const double wet1 =
        saastamoinen_delay(kSpirentRx, r.el_rad, standard_atmosphere(0.0, 1.0)).wet_m;
    num += (r.tropo_s * kC - hyd) * wet1;
    den += wet1 * wet1;
  }
  const double rh = num / den;
  EXPECT_NEAR(rh, 0.77, 0.02);

  // Errors per elevation bin: [30,45), [45,60), [60,75), [75,90] deg.
  const Meteo m = standard_atmosphere(0.0, rh);
  double max_err[4] = {0, 0, 0, 0};
  int count[4] = {0, 0, 0, 0};
  for (const auto& r : rows) {
    if (r.el_rad < min_el) continue;
    const double err = saastamoinen_delay(kSpirentRx, r.el_rad, m).total_m() - r.tropo_s * kC;
    const double el_deg = r.el_rad * kRadToDeg;
    const std::size_t bin =
        std::min<std::size_t>(3, static_cast<std::size_t>((el_deg - 30.0) / 15.0));
    max_err[bin] = std::max(max_err[bin], std::abs(err));
    ++count[bin];
    EXPECT_LT(std::abs(err), 0.15) << r.system << " " << r.prn << " el " << el_deg;
    // Measured: about 1 cm at 30 deg falling to 0.3 mm near the zenith.
    EXPECT_LT(std::abs(err), 0.03) << r.system << " " << r.prn << " el " << el_deg;
  }
  std::printf("[ Saastamoinen vs SimGEN ] fitted RH = %.4f; max |error| by elevation: "
              "30-45 %.4f m (%d), 45-60 %.4f m (%d), 60-75 %.4f m (%d), 75-90 %.4f m (%d)\n",
              rh, max_err[0], count[0], max_err[1], count[1], max_err[2], count[2], max_err[3],
              count[3]);
  for (int c : count) EXPECT_GT(c, 0);
}

}  // namespace
}  // namespace navemu
