#pragma once
// GLONASS L1OF/L2OF navigation message (GLONASS ICD edition 5.1, section 4): pure encoders
// from broadcast parameters in SI units to the strings of a superframe, and decoders back.
// A string is 2 s: the idle chip (bit 85, always 0), the string number m (bits 84..81), 72
// data bits (80..9) and the Hamming check bits KX (8..1, 4.7); 15 strings make a 30 s frame,
// 5 frames a 2.5 min superframe (4.3, Figures 4.4 and 4.5). Strings 1-4 carry the
// transmitting satellite's immediate data (4.4, Table 4.5), string 5 and strings 6-15 the
// non-immediate data: system time corrections and the almanac of the constellation, 5 slots
// per frame (4.5, Tables 4.9 and 4.10). Bit numbers below are the ICD's (85 first on air).
//
// Word format. A string is returned as four uint32 words in the form a u-blox receiver
// reports it in UBX-RXM-SFRBX (gnssId 6, numWords 4), as the u-blox F9 integration manuals
// ("Broadcast navigation data", GLONASS) describe it and as the M10 and ZED-F9P captures in
// ../shared/data/receiver_logs/gpsd show for all 594 strings (tests/protocols/
// test_glonass_nav.cpp):
//   word 1 bits 31..0   ICD bits 85..54 (bit 31 = the idle chip, 30..27 = m);
//   word 2 bits 31..0   ICD bits 53..22;
//   word 3 bits 31..11  ICD bits 21..1 (bits 7..0 of the ICD = KX); bits 10..0 zero;
//   word 4 bits 31..16  superframe number, bits 15..8 zero, bits 7..0 frame number 1..5.
// Word 4 is not transmitted: the receiver deduces it ("zero where unknown", u-blox). The
// captures establish its numbering: frame = the frame (1..5) the string belongs to, and the
// superframe number = 1 + the superframe's index in the GLONASS week (superframes counted
// from Sunday 00:00 GLONASS time, 1..4032): the M10 log (2023-06-28, Wednesday, superframes
// 428-430 of the day) carries 2157-2159 = 3 * 576 + 429.., the F9P log (2020-06-11, Thursday,
// superframe 11 of the day) 2316 = 4 * 576 + 12. RTKLIB (ublox.c decode_gnav) keys a frame's
// strings 1-4 on the upper two bytes of word 4.
//
// Numbers. Every signed field is sign-magnitude on the wire (the most significant bit is the
// sign, 1 = negative; 4.4 "Note"), not two's complement. A magnitude rounding to zero keeps
// the sign of its input (so -0.0 is sent as a negative zero, which real satellites do send,
// and decoded back to -0.0). Angles are radians here and semicircles on the wire (pi as
// std::numbers::pi); positions are metres here and kilometres on the wire.
//
// Time. GLONASS time = UTC(SU) + 3 h (3.3.3); GpsTime values convert with the GPS - UTC leap
// seconds the caller gives: GLONASST = GPST - leap + 3 h. tk, tb and the day numbers N_T,
// N_A, N_4 are GLONASS time (Moscow days).
//
// Out-of-range inputs: every quantised field is clamped to its magnitude range (NaN gives 0);
// counters (tb, tk hours/minutes, N_T, N_A, N_4, slots, flags) are clamped to their field;
// the string number to 1..15, the frame number to 1..5.

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "core/nav_data.hpp"
#include "core/time.hpp"

namespace navemu::gnav {

inline constexpr int kStringsPerFrame = 15;
inline constexpr int kFramesPerSuperframe = 5;
inline constexpr double kString_s = 2.0;
inline constexpr double kFrame_s = 30.0;
inline constexpr double kSuperframe_s = 150.0;
// Superframes per GLONASS week (the u-blox superframe number runs 1..4032).
inline constexpr int kSuperframesPerWeek = 4032;

// Four words, in the u-blox RXM-SFRBX form described above.
using GnavString = std::array<std::uint32_t, 4>;

// Immediate-data fields that GlonassEphemeris has no place for (4.4, Table 4.5), and the
// reserved bits real satellites fill (the captures show nonzero bits 48..35 of string 4).
struct GnavImmediateFlags {
  int p1 = 0;                 // 2 bits: tb interval, 00 = 0 min, 01 = 30, 10 = 45, 11 = 60 min
  std::optional<int> p2;      // 1 bit: oddness of tb; empty = tb & 1 (as the captures show)
  int p3 = 1;                 // 1 bit: 1 = five almanac slots in this frame, 0 = four
  int p4 = 0;                 // 1 bit: 1 = updated ephemeris at the next tb
  int p = 3;                  // 2 bits: tau_c / tau_GPS source mode (3 in the captures)
  int l_n = 0;                // 1 bit: health of this satellite (strings 3, 5, 7, ..., 15)
  int b_n_lsbs = 0;           // the two low bits of B_n (only the MSB, from health, is used)
  int f_t = 2;                // 4 bits: URA index F_T (Table 4.4); default 2 = 2.5 m
  int m = 1;                  // 2 bits: satellite type, 01 = GLONASS-M
  double delta_tau_n_s = 0.0;  // 5 bits sign-magnitude, 2^-30 s: L2 - L1 time difference
  std::uint32_t reserved_s4 = 0;  // bits 48..35 of string 4 (14 bits), sent as given
  // The frame start string 1 sends as tk (UTC seconds of week, GlonassEphemeris form); empty:
  // the ephemeris's frame_time_s. An emulator sets it to the frame being sent (GnavSlot).
  std::optional<double> frame_time_s;
};

// A GLONASS ephemeris with the flags, as strings 1-4 carry it. In `eph`: tb (on the 15 min
// grid of the GLONASS day), frame_time_s (UTC seconds of week of the frame start: string 1
// sends it as tk, 30 s resolution), tau_n_s, gamma_n, p/v/a (PZ-90), health (sent as the MSB
// of B_n), age_days (E_n), sat (slot n, 5 bits). frequency_channel is not in strings 1-4
// (u-blox gives it as freqId); the decoder leaves it 0.
struct GnavEphemeris {
  GlonassEphemeris eph;
  GnavImmediateFlags flags;
};

// String 5 (4.5, Table 4.9) and strings 14-15 of frame 5 (GLONASS-M).
struct GnavSystemData {
  int n_a = 0;             // 11 bits: day of the almanac in the four-year interval, 1..1461
  double tau_c_s = 0.0;    // 32 bits sign-magnitude, 2^-31 s: UTC(SU) + 3 h - GLONASS time (3.3.3)
  int n4 = 0;              // 5 bits: four-year interval number, 1 = 1996-1999
  double tau_gps_s = 0.0;  // 22 bits sign-magnitude, 2^-30 s: GPS time - GLONASS time fraction
  // Frame 5 string 14: B1 (11 bits sign-magnitude, 2^-10 s, UT1 - UTC(SU) at the start of
  // day N_A), B2 (10 bits sign-magnitude, 2^-16 s per mean solar day), KP (2 bits, leap
  // second notice); the rest of string 14 (bits 57..9) and string 15 (bits 80..10) are
  // reserved and sent as given here (the captures show them nonzero).
  double b1_s = 0.0;
  double b2_spd = 0.0;
  int kp = 0;
  std::uint64_t reserved_f5s14 = 0;          // 49 bits
  std::array<std::uint32_t, 3> reserved_f5s15{};  // 71 bits, bit 80 = bit 6 of [0]
};

// One almanac slot (strings 6-15, 4.5, Table 4.9).
struct GnavAlmanacEntry {
  int slot = 0;                 // n_A, 5 bits, 1..24
  int c_n = 1;                  // 1 bit: 1 = usable
  int m_n = 1;                  // 2 bits: 01 = GLONASS-M
  double tau_a_s = 0.0;         // 10 bits sign-magnitude, 2^-18 s
  double lambda_rad = 0.0;      // 21 bits sign-magnitude, 2^-20 semicircles
  double delta_i_rad = 0.0;     // 18 bits sign-magnitude, 2^-20 semicircles (i - 63 deg)
  double epsilon = 0.0;         // 15 bits, 2^-20
  double omega_rad = 0.0;       // 16 bits sign-magnitude, 2^-15 semicircles
  double t_lambda_s = 0.0;      // 21 bits, 2^-5 s (GLONASS time of day)
  double delta_t_s = 0.0;       // 22 bits sign-magnitude, 2^-9 s per orbit (draconic period - 43200)
  double delta_t_dot_s = 0.0;   // 7 bits sign-magnitude, 2^-14 s per orbit^2
  int h_a = 0;                  // frequency channel -7..24; sent as 5 bits, -7..-1 as 25..31
};

// The string a satellite transmits at a time (4.3: frames of 30 s from the start of the
// GLONASS day, strings of 2 s; a superframe is 2.5 min, 576 per day), with the u-blox word 4
// numbering and the frame time string 1 carries.
struct GnavSlot {
  int superframe = 1;         // u-blox superframe number, 1..4032 (see above)
  int frame = 1;              // 1..5
  int string = 1;             // 1..15
  double frame_time_s = 0.0;  // UTC seconds of week of the frame's start (GlonassEphemeris form)
};
GnavSlot glonass_slot(GpsTime t, int leap_seconds);

// Day numbers of a GLONASS date: N_4 (1 = 1996-1999) and the day 1..1461 in it (N_T, N_A).
struct GnavDay {
  int n4 = 1;
  int day = 1;
};
GnavDay glonass_day(GpsTime t, int leap_seconds);

// Word 4 in the u-blox form.
std::uint32_t ublox_word4(int superframe, int frame);

// The words of string `string` (1..15) of frame `frame` (1..5). Strings 1-4 from `eph`;
// string 5 from `sys` (and l_n of eph.flags); strings 6-15 of frames 1-4 and 6-13 of frame 5
// carry slot 5 (frame - 1) + (string - 4) / 2 (4.5), whose entry is looked up in `almanac`
// by slot: a slot without entry is sent with every data bit zero (n_A = 0, C_n = 0: no
// satellite), as the ICD leaves the content of an unused slot to the control segment; odd
// strings end with l_n of eph.flags. Strings 14-15 of frame 5 come from `sys`. N_T in
// string 4 is the GLONASS day of eph.tb. Word 4 is ublox_word4(superframe, frame).
GnavString glonass_string(int frame, int string, const GlonassEphemeris& eph, const GnavImmediateFlags& flags,
                          int leap_seconds, const GnavSystemData& sys, std::span<const GnavAlmanacEntry> almanac,
                          int superframe);
// The same with a decoded ephemeris and its flags.
GnavString glonass_string(int frame, int string, const GnavEphemeris& eph, int leap_seconds,
                          const GnavSystemData& sys, std::span<const GnavAlmanacEntry> almanac,
                          int superframe);

// Hamming code of 4.7 over bits 85..9, as a receiver checks it: the syndrome C7..C1 and the
// overall parity C_sigma of bits 1..85.
enum class GnavHamming {
  kOk,            // all checksums zero
  kCheckBitError, // one of beta1..beta7 wrong (C_sigma = 1 and exactly one of C1..C7), data good
  kCorrectable,   // one data bit wrong (C_sigma = 1, two or more of C1..C7): `bit` is it
  kBad,           // C_sigma = 0 with a nonzero syndrome, or C_sigma = 1 alone (which a flipped
                  // beta8 also gives): two or more errors by 4.7 c)
};
struct GnavHammingResult {
  GnavHamming status = GnavHamming::kBad;
  int bit = 0;  // ICD bit number of the wrong bit (kCheckBitError, kCorrectable)
};
GnavHammingResult glonass_hamming(const GnavString& words);
// True when the syndrome is zero and the idle chip is 0 (what the decoders require).
bool glonass_hamming_ok(const GnavString& words);
// The string with a single wrong bit corrected; nullopt when the string has more errors.
std::optional<GnavString> glonass_correct(const GnavString& words);

int glonass_string_number(const GnavString& words);  // bits 84..81
struct GnavUbloxTag {
  int superframe = 0;
  int frame = 0;
};
GnavUbloxTag decode_ublox_tag(const GnavString& words);

// Strings 1-4 of one frame back to the ephemeris. nullopt unless each passes
// glonass_hamming_ok() and carries its string number. The day of tb is N_T of the four-year
// interval `n4` (string 5) when given, else the date with that N_T nearest to `reference`;
// tk is taken within 12 h of tb; tb and the frame time are converted to GPS / UTC time with
// `leap_seconds`.
std::optional<GnavEphemeris> decode_ephemeris(const GnavString& s1, const GnavString& s2,
                                              const GnavString& s3, const GnavString& s4,
                                              int leap_seconds, GpsTime reference,
                                              std::optional<int> n4 = {});

// String 5 back to the system data (B1, B2, KP and the reserved bits left zero); with
// frame 5's strings 14 and 15 also those. nullopt on a bad string or string number.
std::optional<GnavSystemData> decode_system_data(const GnavString& s5);
std::optional<GnavSystemData> decode_system_data(const GnavString& s5, const GnavString& f5s14,
                                                 const GnavString& f5s15);
// The l_n bit of strings 3, 5, 7, ..., 15 (bit 9 of odd strings >= 5, bit 65 of string 3).
std::optional<int> decode_l_n(const GnavString& words);

// A pair of almanac strings (m, m + 1 with m even, 6..14) back to the entry. nullopt on a
// bad string, a wrong pair, or an empty slot (n_A = 0).
std::optional<GnavAlmanacEntry> decode_almanac(const GnavString& first, const GnavString& second);

}  // namespace navemu::gnav
