#pragma once
// BeiDou B1I navigation messages D1 (MEO/IGSO satellites) and D2 (GEO satellites),
// BDS-SIS-ICD-B1I 3.0 section 5: pure encoders from broadcast parameters in SI units to the
// ten 30-bit words of a subframe, and decoders back. Angles are radians here and semicircles on
// the wire (pi = 3.1415926535898, as for GPS); BDT = GPST - 14 s and BDT week = GPS week - 1356
// (5.1.3.2 / 3.3; core/time.hpp), so the GpsTime toe/toc of BeidouEphemeris are sent as BDT.
//
// Subframe structure (5.1.3, 5.2.2): 300 bits in ten words of 30 bits. Word 1 holds
// 26 information bits (preamble 11100010010, 4 reserved bits, FraID, the 8 MSBs of SOW) of
// which the last 11 are protected by one BCH(15,11,1) code (the 4 reserved bits are the only
// unprotected bits of a subframe); words 2-10 hold 22 information
// bits as two BCH(15,11,1) codes. The generator is g(X) = X^4 + X + 1, the 4 check bits follow
// the 11 information bits (5.1.3). On the air, words 2-10 are interleaved bit by bit
// (X1_1 X2_1 X1_2 X2_2 ... P1_4 P2_4).
//
// Word format. A subframe is returned as ten uint32 words in the form a u-blox receiver
// reports them in UBX-RXM-SFRBX (gnssId 3, numWords 10), established on the ZED-F9P capture in
// ../shared/data/receiver_logs/gpsd (11 BeiDou subframes of C19, C26, C29, C35, all D1;
// tests/protocols/test_beidou_nav.cpp), where every word checks only in this reading:
//   bits 31..30  zero;
//   word 1       bits 29..4 the 26 information bits, bits 3..0 the check bits of bits 14..4;
//   words 2-10   de-interleaved: bits 29..19 the first 11 information bits, bits 18..8 the
//                second 11, bits 7..4 the check bits of the first code, bits 3..0 of the second.
// The information bits of a subframe are thus one stream of 26 + 9 x 22 = 224 bits, in which
// the ICD's fields run on across word boundaries (its figures split e.g. toc, TGD2, a0, a1 of
// D1 subframe 1 over two words); RTKLIB (ublox.c, rcvraw.c decode_bds_d1/d2) reads this form.
//
// Out-of-range inputs (as navemu::lnav): the angles M0, Omega0, omega, i0 are reduced to
// [-pi, pi); identifiers and counters (weeks, AODE, AODC, WNa, WNLSF) are sent as their low
// bits; every other field is clamped to its range (NaN gives 0), times of week to
// [0, 604800); FraID is clamped to 1..5 and the page to the subframe's page range, SOW taken
// modulo 604800. Reserved bits are zero (as in the capture).

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "core/nav_data.hpp"
#include "core/time.hpp"

namespace navemu::bdnav {

inline constexpr double kBdsPi = 3.1415926535898;
inline constexpr std::uint32_t kPreamble = 0x712;  // 11100010010 (5.2.4.1)

// Ten words, word 1 first, in the u-blox RXM-SFRBX form described above.
using BdsSubframe = std::array<std::uint32_t, 10>;

enum class NavType { kD1, kD2 };
// D2 is broadcast by the GEO satellites C01-C05 and C59-C63 (5.1.1), D1 by all others.
NavType nav_type_for_prn(int prn);

// A BDT week (full, not modulo 8192) and a whole second of that week.
struct BdtWeekSow {
  int week = 0;
  std::uint32_t sow_s = 0;  // [0, 604800)
};
// The BDT second containing `t` (GPS time), and back.
BdtWeekSow bdt_from_gps(GpsTime t);
GpsTime gps_from_bdt(int bdt_week, double sow_s);

// Klobuchar parameters (5.2.4.7): navemu::KlobucharCoefficients, alpha_n 8 bits signed,
// 2^-30 s, 2^-27 s/sc, 2^-24 s/sc^2, 2^-24 s/sc^3; beta_n 8 bits signed, 2^11 s, 2^14 s/sc,
// 2^16 s/sc^2, 2^16 s/sc^3.

// D1 subframe 5 page 9 (structure 5.2.3, parameters 5.2.4): BDT against GPS, Galileo and GLONASS time. A0 14 bits
// signed, 0.1 ns; A1 16 bits signed, 0.1 ns/s.
struct BdsGnssTimeOffsets {
  double a0_gps_s = 0.0, a1_gps_sps = 0.0;
  double a0_gal_s = 0.0, a1_gal_sps = 0.0;
  double a0_glo_s = 0.0, a1_glo_sps = 0.0;
};

// D1 subframe 5 page 10 (structure 5.2.3, parameters 5.2.4): BDT against UTC.
struct BdsUtcParameters {
  int dt_ls_s = 0;       // delta t_LS, 8 bits signed, s
  int dt_lsf_s = 0;      // delta t_LSF, 8 bits signed, s
  int wn_lsf = 0;        // BDT week of the leap second; sent modulo 256 (8 bits)
  double a0_utc_s = 0.0;    // 32 bits signed, 2^-30 s
  double a1_utc_sps = 0.0;  // 24 bits signed, 2^-50 s/s
  int dn = 0;            // day of the leap second, 0..6, 8 bits
};

// One satellite's almanac (structure 5.2.3, parameters 5.2.4; D1 subframe 4 pages 1-24 = C01-C24, subframe 5 pages
// 1-6 = C25-C30).
struct BdsAlmanacEntry {
  int prn = 0;                   // 1..30, the page's satellite
  double sqrt_a_sqrtm = 0.0;     // 24 bits unsigned, 2^-11 m^1/2
  double af1_sps = 0.0;          // 11 bits signed, 2^-38 s/s
  double af0_s = 0.0;            // 11 bits signed, 2^-20 s
  double omega0_rad = 0.0;       // 24 bits signed, 2^-23 sc
  double e = 0.0;                // 17 bits unsigned, 2^-21
  double delta_i_rad = 0.0;      // 16 bits signed, 2^-19 sc; i = 0.30 sc + delta_i for MEO/IGSO,
                                 // 0 + delta_i for GEO
  double toa_s = 0.0;            // 8 bits unsigned, 2^12 s
  double omega_dot_radps = 0.0;  // 17 bits signed, 2^-38 sc/s
  double omega_rad = 0.0;        // 24 bits signed, 2^-23 sc
  double m0_rad = 0.0;           // 24 bits signed, 2^-23 sc
};

// The almanac and health pages of D1 subframes 4 and 5.
struct BdsAlmanac {
  // Any order; a page whose satellite has no entry is sent with every parameter zero.
  std::span<const BdsAlmanacEntry> entries;
  // Hea_i of C01-C30 (5.2.4), 9 bits each, subframe 5 pages 7
  // (C01-C19) and 8 (C20-C30).
  std::array<int, 30> health{};
  int wna = 0;         // almanac week, sent modulo 256 (page 8)
  double toa_s = 0.0;  // almanac reference time, 8 bits, 2^12 s (page 8)
  int am_ep_id = 0;    // AmEpID, 2 bits at the end of each almanac page (5.2.4)
};

// Everything a satellite broadcasts besides its own ephemeris.
struct BdsBroadcast {
  KlobucharCoefficients iono;
  BdsGnssTimeOffsets time_offsets;
  BdsUtcParameters utc;
  BdsAlmanac almanac;
};

// ---- encoders --------------------------------------------------------------------------------

// D1 subframe `fra_id` (1..5) starting at `at` (its SOW: the BDT second of the leading edge of
// the subframe's preamble, 5.2.4.3). Subframes 1-3 (5.2.3) carry `eph` (WN = the
// week of `at`) and bc.iono; subframes 4/5 carry page `page` (1..24): the almanac pages from
// bc.almanac, subframe 5 pages 7-8 the health, page 9 bc.time_offsets, page 10 bc.utc, pages
// 11-24 of subframe 5 a page with only its Pnum (reserved/extended content not generated).
BdsSubframe d1_subframe(int fra_id, int page, BdtWeekSow at, const BeidouEphemeris& eph,
                        const BdsBroadcast& bc);

// D2 subframe `fra_id` (1..5), page `page`, of the frame starting at `at` (SOW: the BDT second
// of the frame's start, the same in all five subframes of a frame; subframes start at 0.6 s
// steps, 5.3.1). Subframe 1 pages 1-10 (5.3.2) carry eph and bc.iono (page 2);
// subframes 2-4 (pages 1-6) and subframe 5 (pages 1-120) are sent with valid headers and
// Pnum and zero content (integrity, differential, grid and almanac data not generated).
BdsSubframe d2_subframe(int fra_id, int page, BdtWeekSow at, const BeidouEphemeris& eph,
                        const BdsBroadcast& bc);

// ---- schedules (5.2.2 D1, 5.3.1 D2) ------------------------------------------------------------

// What a satellite transmits at a BDT second of week.
struct BdsSlot {
  int fra_id = 1;
  int page = 0;         // D1: 1..24 for subframes 4/5, 0 for 1-3; D2: 1..10 (subframe 1),
                        // 1..6 (2-4), 1..120 (5)
  std::uint32_t sow_s = 0;   // the value its SOW field carries
  double start_s = 0.0;      // BDT second of week at which the subframe starts
};
// D1: subframe 6 s, frame (5 subframes) 30 s, superframe 24 frames = 12 min; subframes 4 and 5
// show page (frame number mod 24) + 1. SOW = the subframe's start.
BdsSlot d1_slot_at(double bdt_tow_s);
// D2: subframe 0.6 s, frame 3 s, superframe 120 frames = 6 min; subframe 1 shows page
// (frame mod 10) + 1, subframes 2-4 (frame mod 6) + 1, subframe 5 (frame mod 120) + 1.
// SOW = the frame's start.
BdsSlot d2_slot_at(double bdt_tow_s);

// ---- checks and decoders ---------------------------------------------------------------------

// A subframe from RXM-SFRBX words: nullopt unless exactly 10.
std::optional<BdsSubframe> subframe_from_words(std::span<const std::uint32_t> words);

// True when word 1 carries the preamble, bits 31..30 of every word are zero and all 19 BCH
// codes check.
bool bch_ok(const BdsSubframe& words);

// The as-transmitted (interleaved) 30-bit word 2..10 of a u-blox word, and back.
std::uint32_t interleave_word(std::uint32_t ublox_word);
std::uint32_t deinterleave_word(std::uint32_t air_word);

struct BdsHeader {
  int fra_id = 0;
  std::uint32_t sow_s = 0;
  int page = 0;  // Pnum: D1 subframes 4/5 and D2 subframe 5 7 bits, D2 subframes 1-4 4 bits;
                 // 0 for D1 subframes 1-3
};
// nullopt when bch_ok() fails or FraID is not 1..5.
std::optional<BdsHeader> decode_header(const BdsSubframe& words, NavType type);

// D1 subframes 1, 2, 3 back to the ephemeris of satellite `prn`: toe/toc in the week WN (of
// subframe 1) resolved to within half a week of its SOW; transmission_tow_s = SOW of
// subframe 1. nullopt when a subframe fails bch_ok() or has the wrong FraID.
std::optional<BeidouEphemeris> decode_d1_ephemeris(const BdsSubframe& sf1, const BdsSubframe& sf2,
                                                   const BdsSubframe& sf3, int prn);
std::optional<KlobucharCoefficients> decode_d1_iono(const BdsSubframe& sf1);
// D2 subframe 1 pages 1..10, in page order (pages[k] must be page k + 1).
std::optional<BeidouEphemeris> decode_d2_ephemeris(std::span<const BdsSubframe> pages, int prn);
std::optional<KlobucharCoefficients> decode_d2_iono(const BdsSubframe& page2);

// D1 subframe 5 page 9 / page 10.
std::optional<BdsGnssTimeOffsets> decode_d1_time_offsets(const BdsSubframe& words);
std::optional<BdsUtcParameters> decode_d1_utc(const BdsSubframe& words);
// An almanac page (subframe 4 pages 1-24, subframe 5 pages 1-6), with its AmEpID.
struct BdsAlmanacPage {
  BdsAlmanacEntry entry;
  int am_ep_id = 0;
};
std::optional<BdsAlmanacPage> decode_d1_almanac(const BdsSubframe& words);
// Subframe 5 page 7 (C01-C19) or 8 (C20-C30, WNa, toa): the health of those satellites in
// `health` (the others left as in `base`), wna and toa_s from page 8.
std::optional<BdsAlmanac> decode_d1_health(const BdsSubframe& words, const BdsAlmanac& base = {});

// URA index of a URA in metres (the ICD's URAI table, 5.2.4.5, the same as GPS: the smallest
// N whose upper bound holds it; 15 above 6144 m or for NaN) and the nominal URA of an index
// (2^(1+N/2) m for N <= 6, 2^(N-2) m for 6 < N < 15; 15, "unusable", gives 8192 m so that it
// maps back to 15).
int bds_ura_index(double ura_m);
double bds_ura_m(int ura_index);

}  // namespace navemu::bdnav
