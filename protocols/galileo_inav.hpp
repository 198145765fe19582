#pragma once
// Galileo I/NAV navigation message on E1-B, Galileo OS SIS ICD issue 2.0/2.1 (referred to as
// "the ICD"): pure encoders from broadcast parameters in SI units to the words of one nominal
// page pair, and decoders back. Angles are radians here and semicircles on the wire (pi =
// 3.1415926535898 as in GPS, ICD 5.1.1); the word layouts are those of ICD 4.3.5 (word types
// 0-10, 63), the scale factors those of ICD section 5.1 (ephemeris, clock correction, SISA,
// NeQuick G ionosphere, BGD, signal health and data validity, GST-UTC and GST-GPS conversion).
//
// Word format. An I/NAV word is 128 bits: a 6-bit word type and 122 bits of data (ICD 4.3.5).
// It is sent in a nominal page of two 120-bit page parts, each 1 s (ICD 4.3.2, "I/NAV nominal
// page with bits allocation"):
//   even part: even/odd = 0 (1), page type = 0 (1), word bits 0..111 (112), tail (6)
//   odd part:  even/odd = 1 (1), page type = 0 (1), word bits 112..127 (16), Reserved 1 /
//              OSNMA (40), SAR (22), spare (2), CRC (24), Reserved 2 / SSP (8), tail (6)
// The CRC-24Q (ICD 4.3.2 and 5.1.9.4; generator (1+X)P(X), polynomial 0x1864CFB, no
// initial value or final XOR) covers the 114 bits of the even part before its tail and the
// 82 bits of the odd part before the CRC: 196 bits.
//
// A u-blox receiver reports the pair in one UBX-RXM-SFRBX (gnssId 2, sigId 1 = E1-B, or 5 =
// E5b-I, which carries the same pages) as the even part in words 0..3 and the odd part in
// words 4..7, each part left-aligned in 128 bits (bit 0 of a part = bit 31 of its first
// word), the last 8 bits of words 3 and 7 padding (zero). The bits are the decoded data, no
// symbols, no sync pattern. The ZED-F9P (firmware of the gpsd capture in
// ../shared/data/receiver_logs/gpsd) reports numWords = 9: the 9th word is not documented by
// u-blox (its manuals list 8 words for I/NAV), lies outside the CRC, and is constant per
// satellite and signal over the capture (0x1D08D8D9 for E21 E1-B, 0x00000001 for E21 E5b,
// 0x2D012429 for E13 E5b); it does not depend on the page content. It is carried opaquely
// (InavPageExtras::word9) so that real pages re-encode bit for bit, and is 0 by default.
//
// Time. GST runs with GPS time (core/time.hpp): the GST week is the GPS week - 1024, seconds
// of week are the same. The TOW of word types 0, 5 and 6 is the GST at the START of the page
// pair that carries it, i.e. at the leading edge of the first bit of its even part (not the
// end, unlike the GPS HOW). The ZED-F9P capture shows it: the E5b page with TOW 336492 is
// reported right after the 336494 navigation epoch, when its 2 s have been received, and the
// E1-B word 0 pages carry odd TOWs, the odd seconds at which E1-B pages start (ICD 4.3.2,
// "I/NAV nominal sub-frame layout": T0 is GST modulo 30 s, E1-B even parts at T0 = 1, 3, ...,
// 29; E5b-I even parts at even T0).
//
// Bits that are not derived from navigation data (Reserved 1/OSNMA, SAR, the page spare, the
// SSP or Reserved 2, the spare and reserved bits inside words) are InavPageExtras, which the
// decoder returns as received, so a real page can be rebuilt exactly.
//
// Out-of-range inputs: the angles M0, Omega0, omega and i0 are reduced to [-pi, pi); counters
// and identifiers (IODnav, weeks) are sent as their low bits; every other field is clamped to
// its range (NaN gives 0); times of week to [0, 604800) and then to the field; word types
// other than 0-10 and 63 are sent as word type 63 (dummy word, ICD 4.3.5).

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "core/nav_data.hpp"

namespace navemu::inav {

// pi for semicircle conversions (ICD 5.1.1).
inline constexpr double kGalPi = 3.1415926535898;
// SFRBX words of an I/NAV page pair as the ZED-F9P reports them (8 documented + 1, see above).
inline constexpr std::size_t kSfrbxWords = 9;
// Word types (ICD 4.3.5).
inline constexpr int kWordSpare = 0;
inline constexpr int kWordDummy = 63;

// One page pair in the u-blox form above.
using InavPage = std::array<std::uint32_t, kSfrbxWords>;
// One 128-bit word, bit 0 (the MSB of the word type) = the MSB of byte 0.
using InavWord = std::array<std::uint8_t, 16>;

// System data of word types 5, 6 and 10.
struct InavSystemData {
  // Word 5: NeQuick G effective ionisation level coefficients (ICD 5.1.6).
  double ai0_sfu = 0.0;           // 11 bits unsigned, 2^-2 sfu
  double ai1_sfu_per_deg = 0.0;   // 11 bits signed, 2^-8 sfu/degree
  double ai2_sfu_per_deg2 = 0.0;  // 14 bits signed, 2^-15 sfu/degree^2
  std::array<int, 5> region_flags{};  // ionospheric disturbance flags, regions 1..5, 1 bit each

  // Word 6: GST-UTC conversion (ICD 5.1.7). Weeks are full GST weeks, sent modulo 256.
  double a0_s = 0.0;    // 32 bits signed, 2^-30 s
  double a1_sps = 0.0;  // 24 bits signed, 2^-50 s/s
  int dt_ls_s = 0;      // 8 bits signed, s
  double tot_s = 0.0;   // UTC reference time of week, 8 bits unsigned, 3600 s
  int wnot = 0;         // week of tot
  int wn_lsf = 0;       // week of the leap second
  int dn = 0;           // day of the leap second, 3 bits (1..7)
  int dt_lsf_s = 0;     // 8 bits signed, s

  // Word 10: GST-GPS conversion, GGTO (ICD 5.1.8). WN0G is a full GST week, sent modulo 64.
  double a0g_s = 0.0;    // 16 bits signed, 2^-35 s
  double a1g_sps = 0.0;  // 12 bits signed, 2^-51 s/s
  double t0g_s = 0.0;    // reference time of week, 8 bits unsigned, 3600 s
  int wn0g = 0;
};

// The bits of a page pair that do not come from the navigation data: defaults are what the
// satellites of the ZED-F9P capture sent in 2020 (Reserved 1 zero, SAR 1010...10 and spare
// 10) except for the SSP, which by default follows the ICD's cycle.
struct InavPageExtras {
  std::uint64_t reserved1 = 0;  // 40 bits: "Reserved 1", OSNMA on E1-B since ICD 2.0
  std::uint32_t sar = 0x2AAAAA; // 22 bits: SAR return link (ICD 4.3.8)
  std::uint32_t spare = 2;      // 2 bits
  // 8 bits: SSP on E1-B (ICD 2.0 4.3.2: SSP1 00000100, SSP2 00101011, SSP3 00101111, cycling
  // with (GST - 1 s) modulo 6 s); "Reserved 2" on E5b-I and on satellites not yet upgraded
  // (0xFD throughout the 2020 capture). nullopt: the SSP of the page's start time.
  std::optional<std::uint8_t> ssp;
  std::uint32_t word9 = 0;      // the ZED-F9P's 9th SFRBX word
  // The spare and reserved bits inside the word, left-aligned (first bit = MSB of [0]), in
  // the order they occur: word 0: 88; 1, 2, 4: 2; 5: 23; 6: 3; 7: 6; 8: 1; 63: 122. nullopt:
  // reserved bits zero, spare bits alternating 0101... (as in the capture).
  std::optional<std::array<std::uint32_t, 4>> word_spare;
  int word0_time = 2;  // word 0 "Time" field, 2 bits: 2 ('10') = WN and TOW valid (ICD 4.3.5)
};

// ---- encoding ------------------------------------------------------------------------------

// The 128-bit word of `word_type` for a page starting at GST `gst_week`/`gst_tow_s` (words 0,
// 5, 6 carry them). Words 1-5 come from `eph` (IODnav, SVID from eph.sat, SISA index of
// eph.sisa_m, health bits of eph.health in the RINEX 3.05 layout: bit 0 E1-B DVS, bits 1-2
// E1-B HS, bit 6 E5b DVS, bits 7-8 E5b HS), words 5, 6, 10 from `sys`. Words 7-9 and the
// almanac half of word 10 are "no almanac": IODa 0, SVIDs 0 (dummy), every parameter 0.
InavWord inav_word(int word_type, int gst_week, double gst_tow_s, const GalileoEphemeris& eph,
                   const InavSystemData& sys, const InavPageExtras& extras = {});

// A word in a nominal E1-B page pair starting at `gst_tow_s` (which selects the SSP), with
// CRC, tails and padding, in the SFRBX form.
InavPage inav_page_from_word(const InavWord& word, double gst_tow_s,
                             const InavPageExtras& extras = {});

// Both: the SFRBX words of the E1-B page pair of `word_type` starting at GST week/TOW.
InavPage inav_page(int word_type, int gst_week, double gst_tow_s, const GalileoEphemeris& eph,
                   const InavSystemData& sys, const InavPageExtras& extras = {});

// ---- nominal sub-frame schedule (ICD 4.3.2, "I/NAV nominal sub-frame layout") ---------------

// The two signals that carry I/NAV, each with its own page timing.
enum class InavSignal { kE1B, kE5bI };

// Start (GST seconds of week) of the page pair whose 2 s contain `gst_tow_s`: on E1-B the odd
// second at or before it (pages start at T0 = 1, 3, ..., 29 of every 30 s sub-frame; -1, the
// page that began in the previous week, for tow in [0, 1)), on E5b-I the even one (T0 = 0, 2,
// ..., 28).
double inav_page_start_s(double gst_tow_s, InavSignal signal = InavSignal::kE1B);

// Word type of the page pair containing `gst_tow_s`. E1-B sub-frame slot k = 0..14 (page
// starting at T0 = 2k + 1): 2, 4, 6, 7|9, 8|10, 0, 0, 0, 0, 0, 1, 3, 5, 0, 0, with words 7, 8
// in even sub-frames (floor((GST - 1 s) / 30 s) even; a 720 s frame is 24 sub-frames) and 9,
// 10 in odd ones (ICD 4.3.2, "I/NAV nominal frame layout"). E5b-I (T0 = 2k) sends the same
// with words 1, 3, 5 and 2, 4, 6 swapped, so that a dual-frequency receiver has words 1-6 in
// 15 s (the ZED-F9P capture: E5b word 2 at T0 = 20, 4 at 22, 6 at 24, 1 at 0; E1-B word 1 at
// 21). Issue 2.0 gives slots 5, 6, 7, 9 and 14 to word types 16-22 (reduced CED, FEC2
// Reed-Solomon, ...), which this module does not generate: they are spare words 0 here, as
// they were on the satellites of the 2020 capture.
int inav_word_type_for(double gst_tow_s, InavSignal signal = InavSignal::kE1B);

// "Reserved 2" in place of the SSP on E5b-I pages: 0xFD on every E5b-I page of the capture.
inline constexpr std::uint8_t kE5bReserved2 = 0xFD;

// ---- decoding ------------------------------------------------------------------------------

// CRC-24Q of the page pair in SFRBX form (at least 8 words); false for fewer words.
bool inav_crc_ok(std::span<const std::uint32_t> words);

struct InavDecodedPage {
  int word_type = 0;
  InavWord word{};
  InavPageExtras extras;  // as received (ssp always set; word9 0 when numWords is 8)
};

// A nominal page pair back to its word: nullopt unless there are 8 or 9 words, the CRC
// holds, the first part is even and the second odd, and both page types are nominal (0).
std::optional<InavDecodedPage> decode_inav_page(std::span<const std::uint32_t> words);

// The fields `word` carries, written into `eph` / `sys` (others untouched): words 1-4 the
// ephemeris, clock, SISA and SVID (toe, toc in week `gst_week`, as GPS time); word 5 the
// ionosphere into `sys`, BGDs, health bits (E5a bits left as they were) and the week/TOW into
// `gst_week_out`/`gst_tow_out`; word 6 UTC and TOW; word 10 the GGTO; word 0 WN/TOW. The 8- and
// 6-bit weeks are resolved to the full GST weeks nearest to `gst_week`. False for word types
// without such fields (7-9, 63, unknown).
bool decode_word_into(const InavWord& word, int gst_week, GalileoEphemeris& eph,
                      InavSystemData& sys, int* gst_week_out = nullptr,
                      double* gst_tow_out = nullptr);

// Word type (bits 0..5) of a word.
int word_type_of(const InavWord& word);

// Words 1-5 back to the ephemeris: nullopt unless the word types are 1..5 in order and
// IODnav is the same in words 1-4. The 12-bit GST week of word 5 is resolved to the full
// week nearest `reference_gst_week`; toe and toc are put in the week that makes them nearest
// word 5's TOW. data_sources = I/NAV E1-B with the E5b/E1 clock (bits 0 and 9),
// transmission_tow_s = word 5's TOW.
std::optional<GalileoEphemeris> decode_ephemeris(const InavWord& w1, const InavWord& w2,
                                                 const InavWord& w3, const InavWord& w4,
                                                 const InavWord& w5,
                                                 int reference_gst_week = 1200);

// Words 5, 6 and 10 back to the system data: nullopt unless their word types are 5, 6, 10.
std::optional<InavSystemData> decode_system_data(const InavWord& w5, const InavWord& w6,
                                                 const InavWord& w10,
                                                 int reference_gst_week = 1200);

// SISA index of a SISA in metres (ICD 5.1.11: 0..49 cm by 1 cm, 50..98 cm by 2 cm, 1..1.96 m
// by 4 cm, 2..6 m by 16 cm): the smallest index whose value holds it; 255 (NAPA) for negative,
// NaN or above 6 m. And the SISA of an index: -1 for 255 (NAPA) and the spare 126..254.
int sisa_index(double sisa_m);
double sisa_m(int index);

}  // namespace navemu::inav
