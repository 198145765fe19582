// Galileo I/NAV E1-B pages (OS SIS ICD 4.3, 5.1) against real data:
//  - the Galileo RXM-SFRBX pages of a u-blox ZED-F9P capture (gpsd's regression log; E1-B and
//    E5b-I pages, which share the layout) pass the CRC-24Q, decode to plausible values, and are
//    re-encoded bit for bit, padding and the 9th word included, from the decoded values and the
//    non-navigation bits the decoder carries (InavPageExtras);
//  - the E1-B pages of the capture follow the nominal sub-frame schedule;
//  - a real broadcast ephemeris (RINEX 3 nav of station ESBC, 2020-06-24, E01 I/NAV record)
//    comes back within half an LSB after encoding and decoding;
// then flipped bits, the schedule, SSP cycle, SISA table, saturation and malformed input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <random>
#include <string>
#include <set>
#include <vector>

#include "core/time.hpp"
#include "protocols/galileo_inav.hpp"
#include "tests/protocols/sfrbx_capture.hpp"

namespace navemu::inav {
namespace {

using test::read_sfrbx;
using test::Sfrbx;
using test::shared_file;

const std::string kF9pLog = "receiver_logs/gpsd/ublox-zed-f9p-sfrbx.log";
constexpr int kCaptureGstWeek = 1085;  // GPS week 2109 (2020-06), WN of the capture's word 0


std::vector<Sfrbx> galileo_pages() {
  std::vector<Sfrbx> gal;
  for (auto& s : read_sfrbx(shared_file(kF9pLog)))
    if (s.gnss_id == 2) gal.push_back(s);
  return gal;
}

// ---- the ESBC record (RINEX 3.04 mixed nav, ESBC00DNK_R_20201770000_01D_MN.rnx) -------------

// E01 2020 06 24 23:30:00, data sources 517 (I/NAV E1-B + E5b, E5b/E1 clock), typed in.
GalileoEphemeris esbc_e01() {
  GalileoEphemeris e;
  e.sat = SatId(GnssSystem::kGalileo, 1);
  e.toc = from_week_tow(2111, 343800.0);
  e.af0_s = -8.846933487803e-04;
  e.af1_sps = -7.972289495228e-12;
  e.af2_sps2 = 0.0;
  e.iod_nav = 61;
  e.crs_m = 1.865625000000e+01;
  e.delta_n_radps = 2.656539226950e-09;
  e.m0_rad = -1.832282909549e+00;
  e.cuc_rad = 8.568167686462e-07;
  e.e = 9.650341235101e-05;
  e.cus_rad = 1.049041748047e-05;
  e.sqrt_a_sqrtm = 5.440602037430e+03;
  e.toe = from_week_tow(2111, 343800.0);
  e.cic_rad = 1.862645149231e-09;
  e.omega0_rad = 2.123282284601e-01;
  e.cis_rad = -1.452863216400e-07;
  e.i0_rad = 9.828296477370e-01;
  e.crc_m = 1.298750000000e+02;
  e.omega_rad = -2.778709093141e+00;
  e.omega_dot_radps = -5.216288707934e-09;
  e.idot_radps = -6.996720012901e-10;
  e.data_sources = 517;
  e.sisa_m = 3.12;
  e.health = 0;
  e.bgd_e1e5a_s = -1.862645149231e-09;
  e.bgd_e1e5b_s = -2.095475792885e-09;
  e.transmission_tow_s = 344465.0;
  return e;
}

constexpr double kSc = kGalPi;

std::array<InavWord, 5> words_1_to_5(const GalileoEphemeris& e, int gst_week, double tow,
                                     const InavSystemData& sys = {}) {
  std::array<InavWord, 5> w{};
  for (int t = 1; t <= 5; ++t)
    w[static_cast<std::size_t>(t - 1)] = inav_word(t, gst_week, tow + 2.0 * t, e, sys);
  return w;
}

// ---- the capture ---------------------------------------------------------------------------

TEST(InavCapture, EveryGalileoPageOfTheF9pPassesTheCrc) {
  REQUIRE_SHARED_FILE(kF9pLog);
  const auto pages = galileo_pages();
  ASSERT_EQ(pages.size(), 29u);
  for (const auto& s : pages) {
    EXPECT_EQ(s.num_words, 9);
    EXPECT_TRUE(inav_crc_ok(s.words)) << "E" << s.sv_id;
    EXPECT_TRUE(decode_inav_page(s.words).has_value()) << "E" << s.sv_id;
  }
}

TEST(InavCapture, EveryPageReencodesBitForBitFromItsDecodedFields) {
  REQUIRE_SHARED_FILE(kF9pLog);
  int reencoded = 0;
  for (const auto& s : galileo_pages()) {
    const auto d = decode_inav_page(s.words);
    ASSERT_TRUE(d.has_value());
    GalileoEphemeris eph;
    eph.sat = SatId(GnssSystem::kGalileo, s.sv_id);
    InavSystemData sys;
    int week = kCaptureGstWeek;
    double tow = 0.0;
    decode_word_into(d->word, kCaptureGstWeek, eph, sys, &week, &tow);
    const InavPage again = inav_page(d->word_type, week, tow, eph, sys, d->extras);
    for (std::size_t k = 0; k < kSfrbxWords; ++k)
      EXPECT_EQ(again[k], s.words[k]) << "E" << s.sv_id << " word type " << d->word_type
                                      << " SFRBX word " << k;
    ++reencoded;
  }
  EXPECT_EQ(reencoded, 29);
}

TEST(InavCapture, SpareBitsOfTheCaptureAreTheDefaults) {
  REQUIRE_SHARED_FILE(kF9pLog);
  for (const auto& s : galileo_pages()) {
    const auto d = decode_inav_page(s.words);
    ASSERT_TRUE(d.has_value());
    // The 2 reserved bits of words 1 and 2 are not zero on these satellites (11 and 01, the
    // same on E13 and E21): only the word_spare the decoder carries rebuilds them.
    if (d->word_type == 1 || d->word_type == 2) {
      EXPECT_EQ(d->extras.word_spare.value()[0] >> 30, d->word_type == 1 ? 3u : 1u);
      continue;
    }
    InavPageExtras x = d->extras;
    x.word_spare.reset();  // spare bits 0101...
    GalileoEphemeris eph;
    eph.sat = SatId(GnssSystem::kGalileo, s.sv_id);
    InavSystemData sys;
    int week = kCaptureGstWeek;
    double tow = 0.0;
    decode_word_into(d->word, kCaptureGstWeek, eph, sys, &week, &tow);
    const InavPage again = inav_page(d->word_type, week, tow, eph, sys, x);
    for (std::size_t k = 0; k < kSfrbxWords; ++k)
      EXPECT_EQ(again[k], s.words[k]) << "E" << s.sv_id << " word type " << d->word_type
                                      << " SFRBX word " << k;
  }
}

TEST(InavCapture, DecodedValuesArePlausible) {
  REQUIRE_SHARED_FILE(kF9pLog);
  // E21 on E1-B: words 1, 3, 5 in one sub-frame; E21 on E5b: 2, 4, 6 in the same sub-frame.
  std::array<std::optional<InavWord>, 7> e21{};
  for (const auto& s : galileo_pages()) {
    if (s.sv_id != 21) continue;
    const auto d = decode_inav_page(s.words);
    ASSERT_TRUE(d.has_value());
    if (d->word_type >= 1 && d->word_type <= 6)
      e21[static_cast<std::size_t>(d->word_type)] = d->word;
    if (d->word_type == 0) {
      GalileoEphemeris eph;
      InavSystemData sys;
      int week = 0;
      double tow = -1.0;
      ASSERT_TRUE(decode_word_into(d->word, 1000, eph, sys, &week, &tow));
      EXPECT_EQ(week, kCaptureGstWeek);
      EXPECT_GE(tow, 336492.0);
      EXPECT_LE(tow, 336509.0);
      EXPECT_EQ(d->extras.word0_time, 2);
    }
  }
  for (int t = 1; t <= 6; ++t) ASSERT_TRUE(e21[static_cast<std::size_t>(t)].has_value()) << t;
  const auto eph = decode_ephemeris(*e21[1], *e21[2], *e21[3], *e21[4], *e21[5], 1100);
  ASSERT_TRUE(eph.has_value());
  EXPECT_EQ(eph->sat, SatId(GnssSystem::kGalileo, 21));
  EXPECT_NEAR(eph->sqrt_a_sqrtm, 5440.6, 0.5);  // Galileo MEO, a = 29600 km
  EXPECT_LT(eph->e, 0.01);
  EXPECT_NEAR(eph->i0_rad, 56.0 * kSc / 180.0, 0.05);
  EXPECT_EQ(to_week_tow(eph->toe).week, kCaptureGstWeek + kGstWeek0InGpsWeeks);
  EXPECT_LE(std::abs(seconds_between(eph->toe, from_week_tow(2109, 336505.0))), 4.0 * 3600.0);
  EXPECT_EQ(eph->toe, eph->toc);
  EXPECT_GT(eph->sisa_m, 0.0);
  EXPECT_LE(eph->sisa_m, 6.0);
  EXPECT_EQ(eph->health, 0);
  EXPECT_LT(std::abs(eph->af0_s), 2e-3);
  EXPECT_LT(std::abs(eph->bgd_e1e5a_s), 1e-7);
  EXPECT_DOUBLE_EQ(eph->transmission_tow_s, 336505.0);
  // Word 6: the leap second state of 2020 (GST - UTC 18 s, last leap 2017-01-01).
  GalileoEphemeris unused;
  InavSystemData sys;
  double tow6 = 0.0;
  ASSERT_TRUE(decode_word_into(*e21[6], kCaptureGstWeek, unused, sys, nullptr, &tow6));
  EXPECT_EQ(sys.dt_ls_s, 18);
  EXPECT_EQ(sys.dt_lsf_s, 18);
  EXPECT_LT(std::abs(sys.a0_s), 1e-7);
  EXPECT_DOUBLE_EQ(tow6, 336504.0);  // E5b page starting at 336504 (even seconds on E5b)
}

TEST(InavCapture, E1bPagesFollowTheNominalSubframeSchedule) {
  REQUIRE_SHARED_FILE(kF9pLog);
  // E21 on E1-B: consecutive 2 s pages, the first a word 0 whose TOW is its start.
  std::vector<InavDecodedPage> e1b;
  for (const auto& s : galileo_pages())
    if (s.sv_id == 21 && s.sig_id == 1) e1b.push_back(*decode_inav_page(s.words));
  ASSERT_EQ(e1b.size(), 9u);
  ASSERT_EQ(e1b[0].word_type, 0);
  GalileoEphemeris eph;
  InavSystemData sys;
  double t0 = 0.0;
  decode_word_into(e1b[0].word, kCaptureGstWeek, eph, sys, nullptr, &t0);
  EXPECT_EQ(std::fmod(t0, 2.0), 1.0);  // E1-B pages start at odd seconds
  for (std::size_t i = 0; i < e1b.size(); ++i) {
    const double start = t0 + 2.0 * static_cast<double>(i);
    EXPECT_EQ(inav_word_type_for(start), e1b[i].word_type) << "page at " << start;
    EXPECT_DOUBLE_EQ(inav_page_start_s(start + 1.5), start);
    if (e1b[i].word_type == 0 || e1b[i].word_type == 5) {
      double tow = 0.0;
      decode_word_into(e1b[i].word, kCaptureGstWeek, eph, sys, nullptr, &tow);
      EXPECT_DOUBLE_EQ(tow, start);
    }
  }
}

// The same on E5b-I: pages at even seconds, words 1, 3, 5 and 2, 4, 6 in each other's slots,
// "Reserved 2" 0xFD where E1-B has its SSP.
TEST(InavCapture, E5bPagesFollowTheNominalSubframeSchedule) {
  REQUIRE_SHARED_FILE(kF9pLog);
  for (const int sv : {13, 21}) {
    std::vector<InavDecodedPage> e5b;
    for (const auto& s : galileo_pages())
      if (s.sv_id == sv && s.sig_id == 5) e5b.push_back(*decode_inav_page(s.words));
    ASSERT_EQ(e5b.size(), 10u) << sv;
    ASSERT_EQ(e5b[0].word_type, 0);
    GalileoEphemeris eph;
    InavSystemData sys;
    double t0 = 0.0;
    decode_word_into(e5b[0].word, kCaptureGstWeek, eph, sys, nullptr, &t0);
    EXPECT_EQ(std::fmod(t0, 2.0), 0.0);  // E5b-I pages start at even seconds
    std::set<int> seen;
    for (std::size_t i = 0; i < e5b.size(); ++i) {
      const double start = t0 + 2.0 * static_cast<double>(i);
      EXPECT_EQ(inav_word_type_for(start, InavSignal::kE5bI), e5b[i].word_type) << "page at " << start;
      EXPECT_DOUBLE_EQ(inav_page_start_s(start + 1.5, InavSignal::kE5bI), start);
      EXPECT_EQ(e5b[i].extras.ssp, kE5bReserved2);
      seen.insert(e5b[i].word_type);
    }
    EXPECT_EQ(seen, (std::set<int>{0, 1, 2, 4, 6}));  // the capture's 20 s
  }
}

TEST(InavCapture, NinthWordIsConstantPerSignal) {
  REQUIRE_SHARED_FILE(kF9pLog);
  std::vector<std::pair<int, std::uint32_t>> seen;  // (sv * 16 + sig, word 9)
  for (const auto& s : galileo_pages()) {
    const int key = s.sv_id * 16 + s.sig_id;
    bool found = false;
    for (const auto& [k, w] : seen)
      if (k == key) {
        EXPECT_EQ(w, s.words[8]);
        found = true;
      }
    if (!found) seen.emplace_back(key, s.words[8]);
  }
  EXPECT_EQ(seen.size(), 3u);
}

// ---- round trips ---------------------------------------------------------------------------

TEST(InavRoundTrip, EsbcBroadcastEphemerisWithinHalfAnLsb) {
  const GalileoEphemeris in = esbc_e01();
  const int gst_week = 2111 - kGstWeek0InGpsWeeks;
  const double tow = 344465.0;
  const auto w = words_1_to_5(in, gst_week, tow);
  // Through the pages and back.
  std::array<InavWord, 5> back{};
  for (std::size_t i = 0; i < 5; ++i) {
    const InavPage page = inav_page_from_word(w[i], tow);
    const auto d = decode_inav_page(page);
    ASSERT_TRUE(d.has_value());
    EXPECT_EQ(d->word_type, static_cast<int>(i) + 1);
    back[i] = d->word;
  }
  const auto out = decode_ephemeris(back[0], back[1], back[2], back[3], back[4], 1000);
  ASSERT_TRUE(out.has_value());
  EXPECT_EQ(out->sat, in.sat);
  EXPECT_EQ(out->iod_nav, 61);
  EXPECT_EQ(out->toe, in.toe);
  EXPECT_EQ(out->toc, in.toc);
  EXPECT_NEAR(out->m0_rad, in.m0_rad, std::ldexp(kSc, -32));
  EXPECT_NEAR(out->e, in.e, std::ldexp(1.0, -34));
  EXPECT_NEAR(out->sqrt_a_sqrtm, in.sqrt_a_sqrtm, std::ldexp(1.0, -20));
  EXPECT_NEAR(out->omega0_rad, in.omega0_rad, std::ldexp(kSc, -32));
  EXPECT_NEAR(out->i0_rad, in.i0_rad, std::ldexp(kSc, -32));
  EXPECT_NEAR(out->omega_rad, in.omega_rad, std::ldexp(kSc, -32));
  EXPECT_NEAR(out->idot_radps, in.idot_radps, std::ldexp(kSc, -44));
  EXPECT_NEAR(out->omega_dot_radps, in.omega_dot_radps, std::ldexp(kSc, -44));
  EXPECT_NEAR(out->delta_n_radps, in.delta_n_radps, std::ldexp(kSc, -44));
  EXPECT_NEAR(out->cuc_rad, in.cuc_rad, std::ldexp(1.0, -30));
  EXPECT_NEAR(out->cus_rad, in.cus_rad, std::ldexp(1.0, -30));
  EXPECT_NEAR(out->cic_rad, in.cic_rad, std::ldexp(1.0, -30));
  EXPECT_NEAR(out->cis_rad, in.cis_rad, std::ldexp(1.0, -30));
  EXPECT_NEAR(out->crc_m, in.crc_m, std::ldexp(1.0, -6));
  EXPECT_NEAR(out->crs_m, in.crs_m, std::ldexp(1.0, -6));
  EXPECT_NEAR(out->af0_s, in.af0_s, std::ldexp(1.0, -35));
  EXPECT_NEAR(out->af1_sps, in.af1_sps, std::ldexp(1.0, -47));
  EXPECT_NEAR(out->af2_sps2, in.af2_sps2, std::ldexp(1.0, -60));
  EXPECT_NEAR(out->bgd_e1e5a_s, in.bgd_e1e5a_s, std::ldexp(1.0, -33));
  EXPECT_NEAR(out->bgd_e1e5b_s, in.bgd_e1e5b_s, std::ldexp(1.0, -33));
  EXPECT_DOUBLE_EQ(out->sisa_m, 3.12);
  EXPECT_EQ(out->health, 0);
  EXPECT_DOUBLE_EQ(out->transmission_tow_s, tow + 10.0);
  EXPECT_TRUE(out->inav_clock());
  // The RINEX values are themselves on the grid (to their 13 printed digits).
  EXPECT_EQ(out->crs_m, in.crs_m);
  EXPECT_NEAR(out->cus_rad, in.cus_rad, 1e-12 * std::abs(in.cus_rad));
  EXPECT_NEAR(out->bgd_e1e5a_s, in.bgd_e1e5a_s, 1e-12 * std::abs(in.bgd_e1e5a_s));
  EXPECT_NEAR(out->af0_s, in.af0_s, 1e-12 * std::abs(in.af0_s));
}

TEST(InavRoundTrip, DecodeEphemerisResolvesTheWeekAndToeAcrossTheWeekBoundary) {
  GalileoEphemeris in = esbc_e01();
  in.toe = from_week_tow(2112, 0.0);  // toe at the start of the next week
  in.toc = in.toe;
  const auto w = words_1_to_5(in, 2111 - kGstWeek0InGpsWeeks, 604700.0);
  // Word 5 sent at TOW 604710 of GST week 1087; the 12-bit WN resolved near the reference.
  for (const int reference : {1087, 1087 - 2000, 1087 + 2000}) {
    const auto out = decode_ephemeris(w[0], w[1], w[2], w[3], w[4], reference);
    ASSERT_TRUE(out.has_value());
    EXPECT_EQ(out->toe, in.toe) << reference;
    EXPECT_EQ(out->toc, in.toc) << reference;
  }
  const auto far = decode_ephemeris(w[0], w[1], w[2], w[3], w[4], 1087 + 4096);
  ASSERT_TRUE(far.has_value());
  EXPECT_EQ(to_week_tow(far->toe).week, 2112 + 4096);
}

TEST(InavRoundTrip, HealthBitsInTheRinexLayout) {
  GalileoEphemeris in = esbc_e01();
  for (const int h : {0x001, 0x002, 0x004, 0x040, 0x080, 0x100, 0x1C7}) {
    in.health = h;
    const auto w = words_1_to_5(in, 1087, 344400.0);
    const auto out = decode_ephemeris(w[0], w[1], w[2], w[3], w[4], 1087);
    ASSERT_TRUE(out.has_value());
    EXPECT_EQ(out->health, h);
  }
  in.health = 0x038;  // E5a bits only: not in I/NAV
  const auto w = words_1_to_5(in, 1087, 344400.0);
  EXPECT_EQ(decode_ephemeris(w[0], w[1], w[2], w[3], w[4], 1087)->health, 0);
}

TEST(InavRoundTrip, DifferentIodnavIsRejected) {
  GalileoEphemeris a = esbc_e01();
  GalileoEphemeris b = a;
  b.iod_nav = 62;
  auto w = words_1_to_5(a, 1087, 344400.0);
  w[2] = inav_word(3, 1087, 344406.0, b, {});
  EXPECT_FALSE(decode_ephemeris(w[0], w[1], w[2], w[3], w[4], 1087).has_value());
  // Out of order.
  w = words_1_to_5(a, 1087, 344400.0);
  EXPECT_FALSE(decode_ephemeris(w[1], w[0], w[2], w[3], w[4], 1087).has_value());
}

TEST(InavRoundTrip, SystemDataWords5_6_10) {
  InavSystemData in;
  in.ai0_sfu = 31.75;
  in.ai1_sfu_per_deg = -0.1171875;
  in.ai2_sfu_per_deg2 = 0.00146484375;
  in.region_flags = {1, 0, 1, 1, 0};
  in.a0_s = -2.7939677238464355e-09;
  in.a1_sps = -8.881784197001252e-16;
  in.dt_ls_s = 18;
  in.tot_s = 345600.0;
  in.wnot = 1087;
  in.wn_lsf = 1040;  // sent modulo 256, resolved within 128 weeks of the reference
  in.dn = 7;
  in.dt_lsf_s = 18;
  in.a0g_s = 4.0745362639427185e-09;
  in.a1g_sps = -4.440892098500626e-16;
  in.t0g_s = 345600.0;
  in.wn0g = 1087;
  const GalileoEphemeris eph = esbc_e01();
  const InavWord w5 = inav_word(5, 1087, 344401.0, eph, in);
  const InavWord w6 = inav_word(6, 1087, 344403.0, eph, in);
  const InavWord w10 = inav_word(10, 1087, 344405.0, eph, in);
  const auto out = decode_system_data(w5, w6, w10, 1087);
  ASSERT_TRUE(out.has_value());
  EXPECT_EQ(out->ai0_sfu, in.ai0_sfu);
  EXPECT_EQ(out->ai1_sfu_per_deg, in.ai1_sfu_per_deg);
  EXPECT_EQ(out->ai2_sfu_per_deg2, in.ai2_sfu_per_deg2);
  EXPECT_EQ(out->region_flags, in.region_flags);
  EXPECT_EQ(out->a0_s, in.a0_s);
  EXPECT_EQ(out->a1_sps, in.a1_sps);
  EXPECT_EQ(out->dt_ls_s, 18);
  EXPECT_EQ(out->tot_s, in.tot_s);
  EXPECT_EQ(out->wnot, 1087);
  EXPECT_EQ(out->wn_lsf, 1040);
  EXPECT_EQ(out->dn, 7);
  EXPECT_EQ(out->dt_lsf_s, 18);
  EXPECT_EQ(out->a0g_s, in.a0g_s);
  EXPECT_EQ(out->a1g_sps, in.a1g_sps);
  EXPECT_EQ(out->t0g_s, in.t0g_s);
  EXPECT_EQ(out->wn0g, 1087);
  EXPECT_FALSE(decode_system_data(w6, w5, w10, 1087).has_value());
}

TEST(InavRoundTrip, AnglesWrapAndOtherFieldsSaturate) {
  GalileoEphemeris in = esbc_e01();
  in.m0_rad = kSc + 0.25;           // wraps to -pi + 0.25
  in.omega_rad = -3.0 * kSc;        // -pi
  in.e = 1.5;                       // e is 32 bits of 2^-33: saturates below 0.5
  in.crs_m = 1e6;                   // 16 bits signed of 2^-5 m
  in.af0_s = -1.0;                  // 31 bits signed of 2^-34 s
  in.cuc_rad = std::nan("");        // NaN -> 0
  in.sisa_m = 100.0;                // NAPA
  in.iod_nav = 1024 + 5;            // low 10 bits
  const auto w = words_1_to_5(in, 1087, 344400.0);
  const auto out = decode_ephemeris(w[0], w[1], w[2], w[3], w[4], 1087);
  ASSERT_TRUE(out.has_value());
  EXPECT_NEAR(out->m0_rad, -kSc + 0.25, 1e-9);
  EXPECT_NEAR(out->omega_rad, -kSc, 1e-9);
  EXPECT_EQ(out->e, std::ldexp(std::ldexp(1.0, 32) - 1.0, -33));
  EXPECT_EQ(out->crs_m, std::ldexp(32767.0, -5));
  EXPECT_EQ(out->af0_s, -std::ldexp(1.0, -4));
  EXPECT_EQ(out->cuc_rad, 0.0);
  EXPECT_EQ(out->sisa_m, -1.0);
  EXPECT_EQ(out->iod_nav, 5);
}

// ---- CRC, page structure, malformed input --------------------------------------------------

TEST(InavPage, EveryFlippedBitUnderTheCrcFailsIt) {
  const InavPage page = inav_page(4, 1087, 344401.0, esbc_e01(), {});
  ASSERT_TRUE(inav_crc_ok(page));
  ASSERT_TRUE(decode_inav_page(page).has_value());
  // Even part bits 0..113, odd part bits 0..105 (data, Reserved 1, SAR, spare, CRC).
  int flipped = 0;
  for (int bit = 0; bit < 256; ++bit) {
    const int in_part = bit % 128;
    if (in_part >= (bit < 128 ? 114 : 106)) continue;
    InavPage bad = page;
    bad[static_cast<std::size_t>(bit / 32)] ^= 0x80000000u >> (bit % 32);
    EXPECT_FALSE(inav_crc_ok(bad)) << "bit " << bit;
    EXPECT_FALSE(decode_inav_page(bad).has_value()) << "bit " << bit;
    ++flipped;
  }
  EXPECT_EQ(flipped, 114 + 106);
}

TEST(InavPage, LayoutOfTheSfrbxWords) {
  InavPageExtras x;
  x.ssp = 0x2B;
  x.word9 = 0xDEADBEEF;
  const InavPage page = inav_page(0, 1087, 344401.0, esbc_e01(), {}, x);
  EXPECT_EQ(page[0] >> 30, 0u);            // even, nominal
  EXPECT_EQ((page[0] >> 24) & 0x3Fu, 0u);  // word type 0
  EXPECT_EQ((page[0] >> 22) & 3u, 2u);     // time field '10'
  EXPECT_EQ(page[3] & 0x3FFFu, 0u);        // even tail + pad
  EXPECT_EQ(page[4] >> 30, 2u);            // odd, nominal
  EXPECT_EQ(page[7] & 0x3FFFu, 0u);        // odd tail + pad
  EXPECT_EQ((page[7] >> 14) & 0xFFu, 0x2Bu);  // SSP
  EXPECT_EQ(page[8], 0xDEADBEEFu);
  // WN (12 bits) and TOW (20 bits) at the end of word 0, across the two parts.
  EXPECT_EQ((page[3] >> 18) & 0xFFFu, 1087u);
  const std::uint32_t tow = (((page[3] >> 14) & 0xFu) << 16) | ((page[4] >> 14) & 0xFFFFu);
  EXPECT_EQ(tow, 344401u);
}

TEST(InavPage, SspCyclesWithTheE1bPages) {
  const std::array<std::uint32_t, 3> ssp = {0x04, 0x2B, 0x2F};
  for (int k = 0; k < 30; ++k) {
    const double start = 1.0 + 2.0 * k;
    const InavPage page = inav_page(0, 1087, 340200.0 + start, esbc_e01(), {});
    EXPECT_EQ((page[7] >> 14) & 0xFFu, ssp[static_cast<std::size_t>(k % 3)]) << start;
  }
}

TEST(InavPage, MalformedInputNeverCrashes) {
  std::mt19937 rng(7);
  std::vector<std::uint32_t> words;
  for (int n = 0; n < 12; ++n) {
    words.assign(static_cast<std::size_t>(n), 0u);
    for (int trial = 0; trial < 200; ++trial) {
      for (auto& w : words) w = static_cast<std::uint32_t>(rng());
      (void)inav_crc_ok(words);
      const auto d = decode_inav_page(words);
      if (d) {
        GalileoEphemeris e;
        InavSystemData s;
        (void)decode_word_into(d->word, 1087, e, s);
      }
    }
  }
  EXPECT_FALSE(decode_inav_page({}).has_value());
  InavWord junk{};
  for (auto& b : junk) b = 0xFF;
  GalileoEphemeris e;
  InavSystemData s;
  EXPECT_FALSE(decode_word_into(junk, 1087, e, s));  // word type 63
  EXPECT_FALSE(decode_ephemeris(junk, junk, junk, junk, junk).has_value());
  EXPECT_EQ(word_type_of(inav_word(42, 1087, 0.0, e, s)), kWordDummy);
}

// ---- schedule and SISA ---------------------------------------------------------------------

TEST(InavSchedule, NominalE1bSubframe) {
  const std::array<int, 15> even = {2, 4, 6, 7, 8, 0, 0, 0, 0, 0, 1, 3, 5, 0, 0};
  const std::array<int, 15> odd = {2, 4, 6, 9, 10, 0, 0, 0, 0, 0, 1, 3, 5, 0, 0};
  for (int sub = 0; sub < 4; ++sub) {
    for (int k = 0; k < 15; ++k) {
      const double start = 30.0 * sub + 1.0 + 2.0 * k;
      const int want = (sub % 2 == 0 ? even : odd)[static_cast<std::size_t>(k)];
      EXPECT_EQ(inav_word_type_for(start), want) << start;
      EXPECT_EQ(inav_word_type_for(start + 1.999), want) << start;
      EXPECT_DOUBLE_EQ(inav_page_start_s(start + 1.0), start);
    }
  }
  // The page starting at 604799 runs into the next week; TOW 0 still belongs to it.
  EXPECT_DOUBLE_EQ(inav_page_start_s(0.5), -1.0);
  EXPECT_EQ(inav_word_type_for(0.5), inav_word_type_for(604799.0));
  EXPECT_EQ(inav_word_type_for(604799.0), 0);
  EXPECT_EQ(inav_word_type_for(1.0), 2);
  EXPECT_EQ(inav_word_type_for(604800.0 + 7.0), 7);
}

TEST(InavSchedule, NominalE5bSubframe) {
  const std::array<int, 15> even = {1, 3, 5, 7, 8, 0, 0, 0, 0, 0, 2, 4, 6, 0, 0};
  const std::array<int, 15> odd = {1, 3, 5, 9, 10, 0, 0, 0, 0, 0, 2, 4, 6, 0, 0};
  for (int sub = 0; sub < 4; ++sub) {
    for (int k = 0; k < 15; ++k) {
      const double start = 30.0 * sub + 2.0 * k;
      const int want = (sub % 2 == 0 ? even : odd)[static_cast<std::size_t>(k)];
      EXPECT_EQ(inav_word_type_for(start, InavSignal::kE5bI), want) << start;
      EXPECT_EQ(inav_word_type_for(start + 1.999, InavSignal::kE5bI), want) << start;
      EXPECT_DOUBLE_EQ(inav_page_start_s(start + 1.0, InavSignal::kE5bI), start);
    }
  }
  EXPECT_DOUBLE_EQ(inav_page_start_s(0.5, InavSignal::kE5bI), 0.0);
  EXPECT_EQ(inav_word_type_for(604798.5, InavSignal::kE5bI), 0);
}

TEST(InavSisa, IndexTable) {
  EXPECT_EQ(sisa_index(0.0), 0);
  EXPECT_EQ(sisa_index(0.49), 49);
  EXPECT_EQ(sisa_index(0.50), 50);
  EXPECT_EQ(sisa_index(0.51), 51);  // 0.52 m holds it
  EXPECT_EQ(sisa_index(1.00), 75);
  EXPECT_EQ(sisa_index(2.00), 100);
  EXPECT_EQ(sisa_index(3.12), 107);
  EXPECT_EQ(sisa_index(6.00), 125);
  EXPECT_EQ(sisa_index(6.01), 255);
  EXPECT_EQ(sisa_index(-1.0), 255);
  EXPECT_EQ(sisa_index(std::nan("")), 255);
  for (int i = 0; i <= 125; ++i) EXPECT_EQ(sisa_index(sisa_m(i)), i) << i;
  EXPECT_EQ(sisa_m(255), -1.0);
  EXPECT_EQ(sisa_m(200), -1.0);
}

}  // namespace
}  // namespace navemu::inav
