// Jamming: the effective C/N0 (Kaplan & Hegarty section 9.2.2), the event ramps and the front
// end's monitors, checked against numbers worked out independently of models/interference.cpp.

#include "models/interference.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

namespace navemu {
namespace {

constexpr double kCaChipRate_Hz = 1.023e6;

BandInterference jammer(double j_over_s_db, InterferenceKind k) {
  BandInterference i;
  i.add(j_over_s_db, k);
  return i;
}

// The rule of thumb for C/A under strong noise jamming: C/N0 = 10 log10(2 Rc) - J/S
// = 63.1 dB-Hz - J/S (e.g. J/S 50 dB leaves 13 dB-Hz), whatever the clear C/N0 was.
TEST(Interference, StrongWidebandJammingOnCaLeaves63MinusJs) {
  for (double js : {50.0, 55.0, 60.0})
    for (double cn0 : {40.0, 45.0, 50.0})
      EXPECT_NEAR(effective_cn0_dbhz(cn0, jammer(js, InterferenceKind::kWideband), kCaChipRate_Hz),
                  63.1 - js, 0.1)
          << "J/S " << js << " dB, C/N0 " << cn0 << " dB-Hz";
}

// The formula over a sweep of J/S, against the sum of the inverse ratios written out here:
// 45 dB-Hz and J/S 30 dB wideband: 1 / (10^-4.5 + 10^3 / (2 x 1.023e6)) -> 32.84 dB-Hz.
TEST(Interference, EffectiveCn0FollowsTheFormulaOverASweep) {
  EXPECT_NEAR(effective_cn0_dbhz(45.0, jammer(30.0, InterferenceKind::kWideband), kCaChipRate_Hz), 32.84, 0.01);
  for (double js = 0.0; js <= 70.0; js += 5.0) {
    const double q[] = {1.0, 1.5, 2.0};
    const InterferenceKind kinds[] = {InterferenceKind::kCw, InterferenceKind::kMatchedSpectrum,
                                      InterferenceKind::kWideband};
    for (int k = 0; k < 3; ++k) {
      const double expected =
          -10.0 * std::log10(std::pow(10.0, -4.5) + std::pow(10.0, js / 10.0) / (q[k] * kCaChipRate_Hz));
      EXPECT_NEAR(effective_cn0_dbhz(45.0, jammer(js, kinds[k]), kCaChipRate_Hz), expected, 1e-9);
    }
  }
  EXPECT_EQ(effective_cn0_dbhz(45.0, BandInterference{}, kCaChipRate_Hz), 45.0) << "no jammer";
  // J/S 0 dB costs 0.07 dB; the wider spectrum of L5 (10.23 Mchip/s) resists 10 dB more.
  EXPECT_NEAR(effective_cn0_dbhz(45.0, jammer(0.0, InterferenceKind::kWideband), kCaChipRate_Hz), 44.93, 0.01);
  EXPECT_NEAR(effective_cn0_dbhz(45.0, jammer(60.0, InterferenceKind::kWideband), 10.23e6), 63.1 + 10.0 - 60.0, 0.1);
}

// At equal J/S a CW jammer on a spectral line costs 10 log10(2) = 3 dB more than wideband noise;
// two jammers of 40 dB are one of 43 dB.
TEST(Interference, SpectraAndPowersCombine) {
  const double cw = effective_cn0_dbhz(45.0, jammer(60.0, InterferenceKind::kCw), kCaChipRate_Hz);
  const double wb = effective_cn0_dbhz(45.0, jammer(60.0, InterferenceKind::kWideband), kCaChipRate_Hz);
  EXPECT_NEAR(wb - cw, 3.0, 0.05);
  BandInterference two;
  two.add(40.0, InterferenceKind::kWideband);
  two.add(40.0, InterferenceKind::kWideband);
  EXPECT_NEAR(effective_cn0_dbhz(45.0, two, kCaChipRate_Hz),
              effective_cn0_dbhz(45.0, jammer(40.0 + 10.0 * std::log10(2.0), InterferenceKind::kWideband),
                                 kCaChipRate_Hz),
              1e-9);
  EXPECT_FALSE(BandInterference{}.any());
}

TEST(Interference, EventLevelIsATrapezoid) {
  const EventWindow w{10.0, 40.0, 10.0};
  EXPECT_EQ(event_level(w, 9.99), 0.0);
  EXPECT_EQ(event_level(w, 10.0), 0.0);
  EXPECT_NEAR(event_level(w, 15.0), 0.5, 1e-12);
  EXPECT_EQ(event_level(w, 20.0), 1.0);
  EXPECT_EQ(event_level(w, 40.0), 1.0);
  EXPECT_NEAR(event_level(w, 45.0), 0.5, 1e-12);
  EXPECT_EQ(event_level(w, 50.0), 0.0);
  const EventWindow step{10.0, 5.0, 0.0};
  EXPECT_EQ(event_level(step, 10.0), 1.0);
  EXPECT_EQ(event_level(step, 14.999), 1.0);
  EXPECT_EQ(event_level(step, 15.0), 0.0);
  // A live event on a 5 Hz epoch for 2 s: every epoch (seconds from the origin, as the receiver
  // counts them, exact to the ns) from its start is in it, and the epoch on its end is not, for
  // every start (start + 2.0 in double lands an ulp past the end epoch for 15 of these).
  for (std::int64_t k = 1; k < 20000; ++k) {
    const auto epoch_s = [](std::int64_t n) { return seconds_between(GpsTime{n * 200'000'000}, GpsTime{}); };
    const EventWindow live{epoch_s(k), 2.0};
    ASSERT_EQ(event_level(live, epoch_s(k)), 1.0) << k;
    ASSERT_EQ(event_level(live, epoch_s(k + 9)), 1.0) << k;
    ASSERT_EQ(event_level(live, epoch_s(k + 10)), 0.0) << k;
  }
  // A jammer's ramp is linear in dB over the 40 dB below its peak.
  EXPECT_FALSE(ramped_j_over_s_db(50.0, 0.0).has_value());
  EXPECT_DOUBLE_EQ(*ramped_j_over_s_db(50.0, 0.25), 20.0);
  EXPECT_DOUBLE_EQ(*ramped_j_over_s_db(50.0, 0.5), 30.0);
  EXPECT_DOUBLE_EQ(*ramped_j_over_s_db(50.0, 1.0), 50.0);
}

// The monitors: J/N = J/S + S/N with S/N = 43.5 dB-Hz - 10 log10(2.046 MHz) = -19.61 dB.
// Wideband J/S 40 dB: J/N 20.39 dB, the AGC drops 10 log10(1 + 10^2.039) = 20.43 dB x 136.5
// counts; noise rises by 1 + 10^4.35 x 10^4 / (2 x 1.023e6) = 110.4 times. CW J/S 40 dB:
// jamInd up by 5 per dB of J/N.
TEST(Interference, FrontEndMonitorsFollowJamToNoise) {
  const FrontEndReading open_sky{81, 5265, 11};
  const FrontEndMonitor clear = front_end_monitor(open_sky, BandInterference{}, kCaChipRate_Hz);
  EXPECT_EQ(clear.reading.agc_cnt, 5265);
  EXPECT_EQ(clear.reading.noise_per_ms, 81);
  EXPECT_EQ(clear.reading.jam_ind, 11);
  EXPECT_LT(clear.broadband_j_over_n_db, -100.0);

  const FrontEndMonitor wb = front_end_monitor(open_sky, jammer(40.0, InterferenceKind::kWideband), kCaChipRate_Hz);
  EXPECT_NEAR(wb.broadband_j_over_n_db, 20.39, 0.01);
  EXPECT_LT(wb.cw_j_over_n_db, -100.0);
  EXPECT_NEAR(wb.reading.agc_cnt, 5265 - 20.43 * 8191.0 / 60.0, 2.0);
  EXPECT_NEAR(wb.reading.noise_per_ms, 81 * 110.4, 5.0);
  EXPECT_EQ(wb.reading.jam_ind, 11) << "the CW indicator ignores broadband noise";

  const FrontEndMonitor cw = front_end_monitor(open_sky, jammer(40.0, InterferenceKind::kCw), kCaChipRate_Hz);
  EXPECT_NEAR(cw.cw_j_over_n_db, 20.39, 0.01);
  EXPECT_EQ(cw.reading.jam_ind, 11 + 102);
  const FrontEndMonitor huge = front_end_monitor(open_sky, jammer(120.0, InterferenceKind::kCw), kCaChipRate_Hz);
  EXPECT_EQ(huge.reading.jam_ind, 255);
  EXPECT_EQ(huge.reading.agc_cnt, 0);
  EXPECT_EQ(huge.reading.noise_per_ms, 65535);
}

}  // namespace
}  // namespace navemu
