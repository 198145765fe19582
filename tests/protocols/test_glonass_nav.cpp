// GLONASS L1OF navigation strings (GLONASS ICD 5.1, section 4) against real data:
//  - the 594 GLONASS RXM-SFRBX strings of a u-blox M10 capture (a full superframe of several
//    satellites) and a ZED-F9P capture (gpsd's regression logs) pass the Hamming check, sit
//    where the schedule of 4.3 puts them (string, frame and u-blox superframe number against
//    the receivers' NAV-TIMEGPS), and are re-encoded bit for bit, word 4 included, from their
//    decoded values;
//  - a real broadcast ephemeris (RINEX nav of ESBC00DNK, 2020-06-25) survives strings 1-4;
// then random round trips, sign-magnitude, the Hamming code's single-error handling, the
// superframe's layout and decoders fed with garbage.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "protocols/glonass_nav.hpp"
#include "tests/protocols/sfrbx_capture.hpp"

namespace navemu::gnav {
namespace {

using test::shared_file;

const std::string kM10Log = "receiver_logs/gpsd/ublox-glo.log";
const std::string kF9pLog = "receiver_logs/gpsd/ublox-zed-f9p-sfrbx.log";
constexpr int kLeap = 18;  // GPS - UTC at both captures (2020, 2023)

// The GLONASS strings of a capture (tests/protocols/sfrbx_capture.hpp) as GnavStrings.
struct Sfrbx {
  int sv_id = 0;
  int freq_id = 0;
  int num_words = 0;
  GnavString words{};
  std::optional<GpsTime> time;  // of the NAV-TIMEGPS before it
};

std::vector<Sfrbx> read_glonass_sfrbx(const std::filesystem::path& path) {
  std::vector<Sfrbx> out;
  for (const test::Sfrbx& s : test::read_sfrbx(path, 6))
    if (s.words.size() == 4) out.push_back({s.sv_id, s.freq_id, s.num_words, {s.words[0], s.words[1], s.words[2], s.words[3]}, s.time});
  return out;
}

std::vector<Sfrbx> both_captures() {
  auto a = read_glonass_sfrbx(shared_file(kM10Log));
  const auto f = read_glonass_sfrbx(shared_file(kF9pLog));
  a.insert(a.end(), f.begin(), f.end());
  return a;
}

TEST(GnavCapture, EveryStringPassesHammingAndHasTheUbloxLayout) {
  REQUIRE_SHARED_FILE(kM10Log);
  REQUIRE_SHARED_FILE(kF9pLog);
  const auto all = both_captures();
  ASSERT_EQ(all.size(), 594u);  // 584 from the M10, 10 from the F9P
  for (const auto& s : all) {
    SCOPED_TRACE(testing::Message() << "R" << s.sv_id << " " << std::hex << s.words[0]);
    EXPECT_EQ(s.num_words, 4);
    EXPECT_TRUE(glonass_hamming_ok(s.words));
    EXPECT_EQ(glonass_hamming(s.words).status, GnavHamming::kOk);
    EXPECT_EQ(s.words[0] >> 31, 0u);             // the idle chip
    EXPECT_EQ(s.words[2] & 0x7FFu, 0u);          // 85 bits end at word 3 bit 11
    EXPECT_EQ((s.words[3] >> 8) & 0xFFu, 0u);    // word 4: superframe | 0 | frame
    const int m = glonass_string_number(s.words);
    EXPECT_GE(m, 1);
    EXPECT_LE(m, 15);
    const GnavUbloxTag tag = decode_ublox_tag(s.words);
    EXPECT_GE(tag.frame, 1);
    EXPECT_LE(tag.frame, 5);
  }
}

// The receivers output a string with the NAV-TIMEGPS of the epoch 2 s after its start: the
// string, frame and superframe number of the string starting then follow 4.3 (frames from
// the start of the GLONASS day) and the u-blox word 4 numbering (superframe of the week + 1).
TEST(GnavCapture, ScheduleAndWord4MatchTheReceiversTime) {
  REQUIRE_SHARED_FILE(kM10Log);
  REQUIRE_SHARED_FILE(kF9pLog);
  int checked = 0;
  for (const auto& s : both_captures()) {
    ASSERT_TRUE(s.time.has_value());
    const GnavSlot slot = glonass_slot(s.time->plus_s(-2.0), kLeap);
    const GnavUbloxTag tag = decode_ublox_tag(s.words);
    EXPECT_EQ(slot.string, glonass_string_number(s.words));
    EXPECT_EQ(slot.frame, tag.frame);
    EXPECT_EQ(slot.superframe, tag.superframe);
    ++checked;
  }
  EXPECT_EQ(checked, 594);
}

// Decode each frame's strings and encode them again from the decoded values.
TEST(GnavCapture, EveryStringReencodesBitForBit) {
  REQUIRE_SHARED_FILE(kM10Log);
  REQUIRE_SHARED_FILE(kF9pLog);
  const auto all = both_captures();
  // (superframe, frame, svId) -> string number -> the string (each frame of each SV once).
  std::map<std::tuple<int, int, int>, std::map<int, Sfrbx>> frames;
  for (const auto& s : all) {
    const GnavUbloxTag tag = decode_ublox_tag(s.words);
    frames[{tag.superframe, tag.frame, s.sv_id}][glonass_string_number(s.words)] = s;
  }
  std::size_t reencoded = 0;
  std::size_t strings = 0;
  int ephemerides = 0;
  for (const auto& [key, str] : frames) {
    const auto [superframe, frame, sv] = key;
    strings += str.size();
    auto has = [&](int m) { return str.count(m) != 0; };
    auto at = [&](int m) -> const GnavString& { return str.at(m).words; };
    auto expect_same = [&](int m, const GnavString& w) {
      EXPECT_EQ(w, at(m)) << "R" << sv << " superframe " << superframe << " frame " << frame
                          << " string " << m;
      ++reencoded;
    };
    // l_n of the transmitting satellite, from any string that has it.
    GnavEphemeris ln_only;
    for (const auto& [m, s] : str)
      if (auto ln = decode_l_n(s.words)) ln_only.flags.l_n = *ln;

    std::optional<GnavSystemData> sys;
    if (has(5)) {
      sys = decode_system_data(at(5));
      if (frame == 5 && has(14) && has(15)) sys = decode_system_data(at(5), at(14), at(15));
      ASSERT_TRUE(sys.has_value());
      EXPECT_GE(sys->n4, 6);  // 2020-2023
      expect_same(5, glonass_string(frame, 5, ln_only, kLeap, *sys, {}, superframe));
      if (frame == 5 && has(14) && has(15)) {
        expect_same(14, glonass_string(5, 14, ln_only, kLeap, *sys, {}, superframe));
        expect_same(15, glonass_string(5, 15, ln_only, kLeap, *sys, {}, superframe));
      }
    }
    if (has(1) && has(2) && has(3) && has(4)) {
      const GpsTime ref = *str.at(1).time;
      const auto eph = decode_ephemeris(at(1), at(2), at(3), at(4), kLeap, ref,
                                        sys ? std::optional<int>(sys->n4) : std::nullopt);
      ASSERT_TRUE(eph.has_value());
      ++ephemerides;
      EXPECT_EQ(eph->eph.sat.number(), sv);
      const double r = eph->eph.p_pz90_m.norm();
      EXPECT_GT(r, 25.3e6);  // GLONASS orbit radius about 25 510 km
      EXPECT_LT(r, 25.7e6);
      // PZ-90 velocity is Earth-fixed; the inertial speed of a circular orbit is ~3950 m/s.
      const Vec3& p = eph->eph.p_pz90_m;
      const Vec3 inertial = eph->eph.v_pz90_mps + 7.292115e-5 * Vec3(-p.y(), p.x(), 0.0);
      EXPECT_NEAR(inertial.norm(), 3950.0, 60.0);
      EXPECT_LT(std::fabs(seconds_between(eph->eph.tb, ref)), 3600.0);  // tb within the hour
      // tk: the start of this frame, the time string 1 started minus its place in the frame.
      const GnavSlot slot = glonass_slot(ref.plus_s(-2.0), kLeap);
      EXPECT_EQ(eph->eph.frame_time_s, slot.frame_time_s);
      for (int m = 1; m <= 4; ++m)
        expect_same(m, glonass_string(frame, m, *eph, kLeap, {}, {}, superframe));
    }
    for (int m = 6; m <= 14; m += 2) {
      if (frame == 5 && m == 14) break;
      if (!has(m) || !has(m + 1)) continue;
      const auto entry = decode_almanac(at(m), at(m + 1));
      ASSERT_TRUE(entry.has_value());
      EXPECT_EQ(entry->slot, 5 * (frame - 1) + (m - 4) / 2);  // 4.5: the slot order
      const std::vector<GnavAlmanacEntry> almanac = {*entry};
      expect_same(m, glonass_string(frame, m, ln_only, kLeap, {}, almanac, superframe));
      expect_same(m + 1, glonass_string(frame, m + 1, ln_only, kLeap, {}, almanac, superframe));
    }
  }
  EXPECT_EQ(strings, 594u);
  EXPECT_GE(ephemerides, 9);
  // Strings whose frame lacks a partner (a lone almanac string, strings 1-4 incomplete) are
  // not re-encoded; the rest all are.
  EXPECT_GE(reencoded * 10, strings * 8) << reencoded << " of " << strings;
  std::cout << "[          ] re-encoded " << reencoded << " of " << strings << " strings, "
            << ephemerides << " ephemerides\n";
}

// ---- a real broadcast ephemeris ------------------------------------------------------------

// ESBC00DNK_R_20201770000_01D_MN.rnx, R01 2020 06 25 10:15:00 (leap seconds 18), typed in.
GnavEphemeris esbc_r01() {
  GnavEphemeris e;
  e.eph.sat = SatId(GnssSystem::kGlonass, 1);
  e.eph.tb = gps_from_utc(CalendarTime{2020, 6, 25, 10, 15, 0.0}, kLeap);
  e.eph.tau_n_s = -6.358418613672e-05;  // the file's -TauN is +6.358418613672e-05
  e.eph.gamma_n = 0.0;
  e.eph.frame_time_s = 3.816000000000e+05;
  e.eph.p_pz90_m = Vec3(-1.053757666016e+04, 3.707181152344e+03, 2.293765039062e+04) * 1e3;
  e.eph.v_pz90_mps = Vec3(-6.425085067749e-01, -3.071396827698e+00, 2.029142379761e-01) * 1e3;
  e.eph.a_pz90_mps2 = Vec3(1.862645149231e-09, 1.862645149231e-09, -1.862645149231e-09) * 1e3;
  e.eph.health = 0;
  e.eph.frequency_channel = 1;
  e.eph.age_days = 0.0;
  return e;
}

void expect_ephemeris_near(const GnavEphemeris& in, const GnavEphemeris& out) {
  const double km = 1000.0;
  for (Eigen::Index i = 0; i < 3; ++i) {
    EXPECT_NEAR(out.eph.p_pz90_m[i], in.eph.p_pz90_m[i], std::ldexp(km, -12));
    EXPECT_NEAR(out.eph.v_pz90_mps[i], in.eph.v_pz90_mps[i], std::ldexp(km, -21));
    EXPECT_NEAR(out.eph.a_pz90_mps2[i], in.eph.a_pz90_mps2[i], std::ldexp(km, -31));
  }
  EXPECT_NEAR(out.eph.tau_n_s, in.eph.tau_n_s, std::ldexp(1.0, -31));
  EXPECT_NEAR(out.eph.gamma_n, in.eph.gamma_n, std::ldexp(1.0, -41));
  EXPECT_NEAR(out.flags.delta_tau_n_s, in.flags.delta_tau_n_s, std::ldexp(1.0, -31));
  EXPECT_EQ(out.eph.tb, in.eph.tb);
  EXPECT_EQ(out.eph.frame_time_s, in.eph.frame_time_s);
  EXPECT_EQ(out.eph.sat, in.eph.sat);
  EXPECT_EQ(out.eph.health, in.eph.health);
  EXPECT_EQ(out.eph.age_days, in.eph.age_days);
  EXPECT_EQ(out.flags.f_t, in.flags.f_t);
  EXPECT_EQ(out.flags.p1, in.flags.p1);
  EXPECT_EQ(out.flags.p3, in.flags.p3);
  EXPECT_EQ(out.flags.p4, in.flags.p4);
  EXPECT_EQ(out.flags.m, in.flags.m);
  EXPECT_EQ(out.flags.l_n, in.flags.l_n);
}

std::array<GnavString, 4> strings_1_to_4(const GnavEphemeris& e, int superframe = 1) {
  std::array<GnavString, 4> s{};
  for (int m = 1; m <= 4; ++m)
    s[static_cast<std::size_t>(m - 1)] = glonass_string(1, m, e, kLeap, {}, {}, superframe);
  return s;
}

TEST(GnavRinex, EsbcRecordSurvivesStrings1To4) {
  const GnavEphemeris in = esbc_r01();
  const auto s = strings_1_to_4(in);
  const GnavDay day = glonass_day(in.eph.tb, kLeap);
  EXPECT_EQ(day.n4, 7);     // 2020-2023
  EXPECT_EQ(day.day, 177);  // 2020-06-25 is day 177 of the leap year 2020
  for (const std::optional<int> n4 : {std::optional<int>(day.n4), std::optional<int>()}) {
    const auto out = decode_ephemeris(s[0], s[1], s[2], s[3], kLeap, in.eph.tb.plus_s(-5e6), n4);
    ASSERT_TRUE(out.has_value());
    expect_ephemeris_near(in, *out);
    // Broadcast values lie on the grid of Table 4.5: they come back to the 13 digits RINEX
    // prints (1e-5 m of an LSB of 0.49 m, 1e-9 m/s of 0.95 mm/s).
    EXPECT_LT((out->eph.p_pz90_m - in.eph.p_pz90_m).cwiseAbs().maxCoeff(), 1e-5);
    EXPECT_LT((out->eph.v_pz90_mps - in.eph.v_pz90_mps).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LT((out->eph.a_pz90_mps2 - in.eph.a_pz90_mps2).cwiseAbs().maxCoeff(), 1e-18);
    EXPECT_NEAR(out->eph.tau_n_s, in.eph.tau_n_s, 1e-17);
  }
  // tk = 13:00:00 Moscow time (frame time 10:00:00 UTC Thursday), tb = 13:15 = 53 x 15 min.
  // tk is ICD bits 76..65 = word 1 bits 22..11, tb bits 76..70 = bits 22..16, P2 bit 23.
  EXPECT_EQ((s[0][0] >> 11) & 0xFFFu, (13u << 7) | (0u << 1) | 0u);
  EXPECT_EQ((s[1][0] >> 16) & 0x7Fu, 53u);
  EXPECT_EQ((s[1][0] >> 23) & 0x1u, 1u);  // P2 = oddness of tb
}

// ---- round trips ---------------------------------------------------------------------------

TEST(GnavRoundTrip, RandomEphemerisWithinHalfAnLsb) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const GpsTime t0 = gps_from_utc(CalendarTime{2024, 3, 1, 0, 0, 0.0}, kLeap);
  for (int k = 0; k < 300; ++k) {
    GnavEphemeris e;
    e.eph.sat = SatId(GnssSystem::kGlonass, 1 + k % 24);
    // tb on the 15 min grid within 10 days; the frame 0..30 min before it, on 30 s.
    const GpsTime tb = t0.plus_s(900.0 * (1 + k % 900));
    e.eph.tb = tb;
    const double frame_utc = to_week_tow(tb.plus_s(-kLeap - 30.0 * (k % 60))).tow_s;
    e.eph.frame_time_s = frame_utc;
    e.eph.p_pz90_m = Vec3(u(rng), u(rng), u(rng)) * 2.7e7;
    e.eph.v_pz90_mps = Vec3(u(rng), u(rng), u(rng)) * 4300.0;
    e.eph.a_pz90_mps2 = Vec3(u(rng), u(rng), u(rng)) * 1.4e-5;
    e.eph.tau_n_s = u(rng) * 1.9e-3;
    e.eph.gamma_n = u(rng) * 9e-10;
    e.eph.health = k % 2;
    e.eph.age_days = k % 32;
    e.flags.delta_tau_n_s = u(rng) * 1.3e-8;
    e.flags.f_t = k % 15;
    e.flags.p1 = k % 4;
    e.flags.p3 = k % 2;
    e.flags.p4 = (k / 2) % 2;
    e.flags.l_n = (k / 3) % 2;
    e.flags.m = k % 4;
    const auto s = strings_1_to_4(e);
    for (const auto& w : s) EXPECT_TRUE(glonass_hamming_ok(w));
    const auto out = decode_ephemeris(s[0], s[1], s[2], s[3], kLeap, tb.plus_s(u(rng) * 5e7));
    ASSERT_TRUE(out.has_value());
    expect_ephemeris_near(e, *out);
    // Decoded values are on the grid and re-encode to the same words.
    EXPECT_EQ(strings_1_to_4(*out), s);
  }
}

TEST(GnavRoundTrip, SystemDataAndAlmanac) {
  GnavSystemData sys;
  sys.n_a = 1275;
  sys.tau_c_s = -1.234567e-8;
  sys.n4 = 7;
  sys.tau_gps_s = 3.3e-9;
  sys.b1_s = -0.123;
  sys.b2_spd = 2.1e-4;
  sys.kp = 2;
  sys.reserved_f5s14 = 0x1234567890ABull;
  sys.reserved_f5s15 = {0x55u, 0xDEADBEEFu, 0x12345678u};
  GnavEphemeris e;
  e.flags.l_n = 1;
  const auto s5 = glonass_string(5, 5, e, kLeap, sys, {}, 7);
  const auto s14 = glonass_string(5, 14, e, kLeap, sys, {}, 7);
  const auto s15 = glonass_string(5, 15, e, kLeap, sys, {}, 7);
  const auto out = decode_system_data(s5, s14, s15);
  ASSERT_TRUE(out.has_value());
  EXPECT_EQ(out->n_a, 1275);
  EXPECT_EQ(out->n4, 7);
  EXPECT_NEAR(out->tau_c_s, sys.tau_c_s, std::ldexp(1.0, -32));
  EXPECT_NEAR(out->tau_gps_s, sys.tau_gps_s, std::ldexp(1.0, -31));
  EXPECT_NEAR(out->b1_s, sys.b1_s, std::ldexp(1.0, -11));
  EXPECT_NEAR(out->b2_spd, sys.b2_spd, std::ldexp(1.0, -17));
  EXPECT_EQ(out->kp, 2);
  EXPECT_EQ(out->reserved_f5s14, sys.reserved_f5s14);
  EXPECT_EQ(out->reserved_f5s15, sys.reserved_f5s15);
  EXPECT_EQ(decode_l_n(s5), 1);
  EXPECT_EQ(decode_l_n(s15), 1);

  GnavAlmanacEntry a;
  a.slot = 17;
  a.c_n = 0;
  a.m_n = 1;
  a.tau_a_s = -1.5e-4;
  a.lambda_rad = -2.5;
  a.delta_i_rad = 0.011;
  a.epsilon = 0.0012;
  a.omega_rad = 2.9;
  a.t_lambda_s = 43210.5;
  a.delta_t_s = -2655.3;
  a.delta_t_dot_s = 6.1e-4;
  a.h_a = -5;
  const std::vector<GnavAlmanacEntry> alm = {a};
  // Slot 17 is the second of frame 4: strings 8 and 9.
  const auto s8 = glonass_string(4, 8, e, kLeap, {}, alm, 7);
  const auto s9 = glonass_string(4, 9, e, kLeap, {}, alm, 7);
  const auto back = decode_almanac(s8, s9);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->slot, 17);
  EXPECT_EQ(back->c_n, 0);
  EXPECT_EQ(back->h_a, -5);
  const double pi = 3.141592653589793;
  EXPECT_NEAR(back->tau_a_s, a.tau_a_s, std::ldexp(1.0, -19));
  EXPECT_NEAR(back->lambda_rad, a.lambda_rad, std::ldexp(pi, -21));
  EXPECT_NEAR(back->delta_i_rad, a.delta_i_rad, std::ldexp(pi, -21));
  EXPECT_NEAR(back->epsilon, a.epsilon, std::ldexp(1.0, -21));
  EXPECT_NEAR(back->omega_rad, a.omega_rad, std::ldexp(pi, -16));
  EXPECT_NEAR(back->t_lambda_s, a.t_lambda_s, std::ldexp(1.0, -6));
  EXPECT_NEAR(back->delta_t_s, a.delta_t_s, std::ldexp(1.0, -10));
  EXPECT_NEAR(back->delta_t_dot_s, a.delta_t_dot_s, std::ldexp(1.0, -15));
  // Wrong pairs are refused.
  EXPECT_FALSE(decode_almanac(s9, s8).has_value());
  EXPECT_FALSE(decode_almanac(s8, s5).has_value());
}

TEST(GnavFields, SignMagnitudeAndClamping) {
  GnavEphemeris e;
  e.eph.tau_n_s = -3.0 * std::ldexp(1.0, -30);  // 22 bits: sign 1, magnitude 3
  const auto s4 = glonass_string(1, 4, e, kLeap, {}, {}, 1);
  // tau_n is ICD bits 80..59: word 1 bits 26..5.
  EXPECT_EQ((s4[0] >> 5) & 0x3FFFFFu, (1u << 21) | 3u);
  e.eph.tau_n_s = 1.0;  // far beyond 2^21 - 1 LSBs: the largest magnitude
  const auto big = glonass_string(1, 4, e, kLeap, {}, {}, 1);
  EXPECT_EQ((big[0] >> 5) & 0x3FFFFFu, (1u << 21) - 1u);
  e.eph.tau_n_s = std::nan("");
  EXPECT_EQ((glonass_string(1, 4, e, kLeap, {}, {}, 1)[0] >> 5) & 0x3FFFFFu, 0u);
  // -0.0 stays a negative zero both ways.
  e.eph.tau_n_s = -0.0;
  const auto nz = glonass_string(1, 4, e, kLeap, {}, {}, 1);
  EXPECT_EQ((nz[0] >> 5) & 0x3FFFFFu, 1u << 21);
  const auto s = strings_1_to_4(e);
  const auto out = decode_ephemeris(s[0], s[1], nz, s[3], kLeap, GpsTime{});
  ASSERT_FALSE(out.has_value());  // nz is string 4 in the place of string 3
  const auto ok = decode_ephemeris(s[0], s[1], s[2], nz, kLeap, GpsTime{});
  ASSERT_TRUE(ok.has_value());
  EXPECT_TRUE(std::signbit(ok->eph.tau_n_s));
  // Out-of-range string and frame numbers are clamped.
  EXPECT_EQ(glonass_string_number(glonass_string(1, 99, e, kLeap, {}, {}, 1)), 15);
  EXPECT_EQ(decode_ublox_tag(glonass_string(-3, 1, e, kLeap, {}, {}, 2)).frame, 1);
  EXPECT_EQ(decode_ublox_tag(glonass_string(9, 1, e, kLeap, {}, {}, 2)).superframe, 2);
}

// ---- Hamming code (4.7) --------------------------------------------------------------------

TEST(GnavHamming, EverySingleBitErrorIsDetectedAndLocated) {
  const GnavEphemeris e = esbc_r01();
  for (int m = 1; m <= 4; ++m) {
    const GnavString good = glonass_string(1, m, e, kLeap, {}, {}, 1);
    ASSERT_TRUE(glonass_hamming_ok(good));
    for (int bit = 1; bit <= 85; ++bit) {
      GnavString bad = good;
      const int pos = 85 - bit;
      bad[static_cast<std::size_t>(pos / 32)] ^= 1u << (31 - pos % 32);
      EXPECT_FALSE(glonass_hamming_ok(bad)) << "bit " << bit;
      const GnavHammingResult r = glonass_hamming(bad);
      if (bit == 8) {  // C_sigma alone: 4.7 c) counts it as two or more errors
        EXPECT_EQ(r.status, GnavHamming::kBad);
        EXPECT_FALSE(glonass_correct(bad).has_value());
        continue;
      }
      EXPECT_EQ(r.status, bit < 8 ? GnavHamming::kCheckBitError : GnavHamming::kCorrectable)
          << "bit " << bit;
      EXPECT_EQ(r.bit, bit);
      EXPECT_EQ(glonass_correct(bad), good) << "bit " << bit;
      // A second error is detected and not "corrected".
      for (int bit2 = bit + 1; bit2 <= 85; bit2 += 7) {
        GnavString worse = bad;
        const int pos2 = 85 - bit2;
        worse[static_cast<std::size_t>(pos2 / 32)] ^= 1u << (31 - pos2 % 32);
        EXPECT_EQ(glonass_hamming(worse).status, GnavHamming::kBad) << bit << " " << bit2;
        EXPECT_FALSE(glonass_correct(worse).has_value());
      }
    }
  }
}

TEST(GnavHamming, DecodersRejectAFlippedBit) {
  const GnavEphemeris e = esbc_r01();
  auto s = strings_1_to_4(e);
  s[1][1] ^= 0x100u;
  EXPECT_FALSE(decode_ephemeris(s[0], s[1], s[2], s[3], kLeap, e.eph.tb).has_value());
  // ... and the idle chip set is not a string.
  s = strings_1_to_4(e);
  s[2][0] ^= 0x80000000u;
  EXPECT_FALSE(glonass_hamming_ok(s[2]));
}

// ---- schedule and superframe layout (4.3, 4.5) ---------------------------------------------

TEST(GnavSchedule, FramesFromTheStartOfTheGlonassDay) {
  // 2020-06-25 00:00:00 GLONASS time = 2020-06-24 21:00:00 UTC, a Thursday (day 4 of the week).
  const GpsTime day0 = gps_from_utc(CalendarTime{2020, 6, 24, 21, 0, 0.0}, kLeap);
  GnavSlot s = glonass_slot(day0, kLeap);
  EXPECT_EQ(s.frame, 1);
  EXPECT_EQ(s.string, 1);
  EXPECT_EQ(s.superframe, 4 * 576 + 1);
  EXPECT_EQ(s.frame_time_s, 3 * 86400.0 + 21 * 3600.0);  // Wednesday 21:00 UTC
  s = glonass_slot(day0.plus_s(-0.5), kLeap);
  EXPECT_EQ(s.frame, 5);
  EXPECT_EQ(s.string, 15);
  EXPECT_EQ(s.superframe, 4 * 576);
  for (int k = 0; k < 400; ++k) {
    s = glonass_slot(day0.plus_s(2.0 * k + 1.0), kLeap);
    EXPECT_EQ(s.string, k % 15 + 1);
    EXPECT_EQ(s.frame, (k / 15) % 5 + 1);
    EXPECT_EQ(s.superframe, 4 * 576 + 1 + k / 75);
    EXPECT_EQ(s.frame_time_s, 3 * 86400.0 + 21 * 3600.0 + 30.0 * (k / 15));
  }
  // Sunday 00:00 GLONASS time starts superframe 1; the week wraps after 4032.
  const GpsTime sunday = gps_from_utc(CalendarTime{2020, 6, 27, 21, 0, 0.0}, kLeap);
  EXPECT_EQ(glonass_slot(sunday, kLeap).superframe, 1);
  EXPECT_EQ(glonass_slot(sunday.plus_s(-1.0), kLeap).superframe, kSuperframesPerWeek);
}

TEST(GnavSchedule, SuperframeLayout) {
  const GnavEphemeris e = esbc_r01();
  std::vector<GnavAlmanacEntry> almanac;
  for (int slot = 1; slot <= 24; ++slot) {
    if (slot == 9) continue;  // an empty slot
    GnavAlmanacEntry a;
    a.slot = slot;
    a.h_a = slot % 14 - 7;
    a.lambda_rad = 0.1 * slot;
    almanac.push_back(a);
  }
  for (int frame = 1; frame <= 5; ++frame) {
    for (int m = 1; m <= 15; ++m) {
      const GnavString w = glonass_string(frame, m, e, kLeap, {}, almanac, 33);
      EXPECT_TRUE(glonass_hamming_ok(w));
      EXPECT_EQ(glonass_string_number(w), m);
      EXPECT_EQ(w[3], (33u << 16) | static_cast<std::uint32_t>(frame));
      if (m >= 6 && m % 2 == 0 && !(frame == 5 && m == 14)) {
        const int slot = 5 * (frame - 1) + (m - 4) / 2;
        const auto a = decode_almanac(w, glonass_string(frame, m + 1, e, kLeap, {}, almanac, 33));
        if (slot == 9) {
          EXPECT_FALSE(a.has_value());
          // Every data bit of an empty slot's first string is zero.
          EXPECT_EQ(w[0] & 0x07FFFFFFu, 0u);
          EXPECT_EQ(w[1], 0u);
        } else {
          ASSERT_TRUE(a.has_value());
          EXPECT_EQ(a->slot, slot);
          EXPECT_EQ(a->h_a, slot % 14 - 7);
        }
      }
    }
  }
}

// ---- decoders never trust their input ------------------------------------------------------

TEST(GnavDecoders, GarbageNeverCrashes) {
  std::mt19937 rng(5);
  int accepted = 0;
  for (int k = 0; k < 20000; ++k) {
    GnavString w{};
    for (auto& x : w) x = static_cast<std::uint32_t>(rng());
    if (k % 2 == 0) {  // make half of them pass the Hamming check
      if (auto c = glonass_correct(w)) w = *c;
    }
    const GpsTime ref{static_cast<std::int64_t>(rng()) * 1'000'000'000};
    accepted += decode_ephemeris(w, w, w, w, kLeap, ref).has_value() ? 1 : 0;
    accepted += decode_system_data(w).has_value() ? 1 : 0;
    accepted += decode_system_data(w, w, w).has_value() ? 1 : 0;
    accepted += decode_almanac(w, w).has_value() ? 1 : 0;
    (void)decode_l_n(w);
    (void)decode_ublox_tag(w);
    (void)glonass_hamming(w);
  }
  EXPECT_GE(accepted, 0);
}

}  // namespace
}  // namespace navemu::gnav
