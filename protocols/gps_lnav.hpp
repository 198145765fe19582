#pragma once
// GPS L1 C/A legacy navigation message (LNAV), IS-GPS-200 Appendix II (section 20.3): pure
// encoders from broadcast parameters in SI units to the ten 30-bit words of a subframe, and
// decoders back. Angles are radians here and semicircles on the wire (pi = 3.1415926535898,
// IS-GPS-200 20.3.3.4.3.1); the scale factors are those of Tables 20-I (subframe 1),
// 20-III (subframes 2 and 3), 20-VI (almanac) and 20-IX/20-X (ionosphere, UTC).
//
// Word format. A subframe is returned as ten uint32 words in the form a u-blox receiver
// reports them in UBX-RXM-SFRBX (gnssId 0, numWords 10), established on the ZED-F9P capture
// in ../shared/data/receiver_logs/gpsd (tests/protocols/test_lnav.cpp):
//   bits 29..6  d1..d24, the source data bits, never complemented (u-blox integration
//               manuals, UBX-RXM-SFRBX: where the parity algorithm requires data to be
//               inverted, as for GPS L1C/A, the receiver does so before output);
//   bits  5..0  D25..D30, the parity of Table 20-XIV computed over d1..d24 with the
//               D29*, D30* held in bits 31..30;
//   bits 31..30 D29*, D30* "in the receiver's polarity": the receiver complements a word
//               together with its two leading bits whenever the transmitted D30* was 1, so
//               bit 30 is always 0 and bit 31 = D29* xor D30* of the word as transmitted.
// Each word is thus self-checking with its own bits 31..30, which is what both consumers do:
//   - RTKLIB (ublox.c decode_nav) takes bits 29..6 as the data and checks no parity: it needs
//     upright data bits, which this form has;
//   - gpsd (subframe.c gpsd_interpret_subframe_raw, 3.22) complements bits 29..6 when bit 30
//     is set (never here) and checks D25..D30 with bits 31..30 as D29*, D30*.
// The words as transmitted by the satellite differ only where D30* = 1 (data bits
// complemented, parity bits and D29*/D30* as sent); lnav_as_transmitted() converts, and
// lnav_parity_ok() accepts both forms.
//
// Bits 23 and 24 of words 2 and 10 are the non-information bits "t" solved so that D29 and
// D30 of those words are zero as transmitted (20.3.5.2), so every TLM and the word after each
// HOW start upright and the first word of a subframe has D29* = D30* = 0.
//
// Out-of-range inputs: the angles M0, Omega0, omega and i0 are reduced to [-pi, pi); the
// counters and identifiers (weeks, IODC, IODE) are sent as their low bits; every other field
// is clamped to its field's range (NaN gives 0), times of week to [0, 604800); subframe and
// page numbers are clamped to 1..5 and 1..25, the TOW count is taken modulo 100800.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace navemu::lnav {

// pi for semicircle conversions (IS-GPS-200 20.3.3.4.3.1), as receivers and RINEX use it.
inline constexpr double kGpsPi = 3.1415926535898;
// TLM preamble (20.3.3.1).
inline constexpr std::uint32_t kPreamble = 0x8B;
// HOW TOW count: 6 s units, 0..100799 (20.3.3.2).
inline constexpr std::uint32_t kTowCountsPerWeek = 100800;

// Ten words, word 1 (TLM) first, in the u-blox RXM-SFRBX form described above.
using LnavSubframe = std::array<std::uint32_t, 10>;

// One SV's clock and ephemeris data (subframes 1-3) plus the TLM/HOW flags it transmits.
// Field names and units mirror core/nav_data.hpp (GpsEphemeris) where both have a field.
struct LnavEphemeris {
  int sv_id = 0;  // the SV's PRN 1..32; not transmitted in subframes 1-3, carried for the caller

  // Subframe 1 (Figure 20-1 sheet 1, Table 20-I).
  int week = 0;           // full GPS week of transmission; sent modulo 1024 (10 bits)
  int codes_on_l2 = 1;    // 2 bits: 1 = P code, 2 = C/A code (20.3.3.3.1.2)
  int ura_index = 0;      // 4 bits, 0..15 (20.3.3.3.1.3); see lnav_ura_index()
  int health = 0;         // 6 bits (20.3.3.3.1.4)
  int iodc = 0;           // 10 bits, sent modulo 1024 (20.3.3.3.1.5)
  int l2p_data_flag = 0;  // 1 bit: 1 = NAV data off on L2 P (20.3.3.3.1.6)
  double tgd_s = 0.0;     // 8 bits signed, 2^-31 s
  double toc_s = 0.0;     // seconds of week, 16 bits unsigned, 2^4 s
  double af2_sps2 = 0.0;  // 8 bits signed, 2^-55 s/s^2
  double af1_sps = 0.0;   // 16 bits signed, 2^-43 s/s
  double af0_s = 0.0;     // 22 bits signed, 2^-31 s

  // Subframes 2 and 3 (Figure 20-1 sheets 2-3, Table 20-III).
  int iode = 0;                  // 8 bits, sent modulo 256 in both subframes; must equal the 8 LSBs
                                 // of iodc (20.3.4.4), or receivers discard the set
  double crs_m = 0.0;            // 16 bits signed, 2^-5 m
  double delta_n_radps = 0.0;    // 16 bits signed, 2^-43 semicircles/s
  double m0_rad = 0.0;           // 32 bits signed, 2^-31 semicircles
  double cuc_rad = 0.0;          // 16 bits signed, 2^-29 rad
  double e = 0.0;                // 32 bits unsigned, 2^-33
  double cus_rad = 0.0;          // 16 bits signed, 2^-29 rad
  double sqrt_a_sqrtm = 0.0;     // 32 bits unsigned, 2^-19 m^1/2
  double toe_s = 0.0;            // seconds of week, 16 bits unsigned, 2^4 s
  int fit_interval_flag = 0;     // 1 bit: 0 = 4 h, 1 = longer (20.3.3.4.3.1, Table 20-XII)
  int aodo = 0;                  // 5 bits, age of data offset in units of 900 s (20.3.3.4.1)
  double cic_rad = 0.0;          // 16 bits signed, 2^-29 rad
  double omega0_rad = 0.0;       // 32 bits signed, 2^-31 semicircles
  double cis_rad = 0.0;          // 16 bits signed, 2^-29 rad
  double i0_rad = 0.0;           // 32 bits signed, 2^-31 semicircles
  double crc_m = 0.0;            // 16 bits signed, 2^-5 m
  double omega_rad = 0.0;        // 32 bits signed, 2^-31 semicircles (argument of perigee)
  double omega_dot_radps = 0.0;  // 24 bits signed, 2^-43 semicircles/s
  double idot_radps = 0.0;       // 14 bits signed, 2^-43 semicircles/s

  // TLM word (20.3.3.1) and HOW (20.3.3.2) content, sent in every subframe.
  int tlm_message = 0;            // 14 bits
  int integrity_status_flag = 0;  // 1 bit
  int alert_flag = 0;             // 1 bit
  int anti_spoof_flag = 0;        // 1 bit
};

// Subframe 4 page 18: Klobuchar ionosphere (20.3.3.5.1.7) and UTC parameters (20.3.3.5.1.6).
struct LnavIonoUtc {
  // alpha_n: 8 bits signed each, 2^-30 s, 2^-27 s/semicircle, 2^-24 s/semicircle^2,
  // 2^-24 s/semicircle^3 (Table 20-X).
  std::array<double, 4> alpha{};
  // beta_n: 8 bits signed each, 2^11 s, 2^14 s/semicircle, 2^16 s/semicircle^2,
  // 2^16 s/semicircle^3.
  std::array<double, 4> beta{};
  double a0_s = 0.0;    // 32 bits signed, 2^-30 s
  double a1_sps = 0.0;  // 24 bits signed, 2^-50 s/s
  double tot_s = 0.0;   // UTC reference time, seconds of week, 8 bits unsigned, 2^12 s
  int wnt = 0;          // full week of tot; sent modulo 256
  int dt_ls_s = 0;      // delta t_LS, 8 bits signed, s
  int wn_lsf = 0;       // full week of the leap second; sent modulo 256
  int dn = 0;           // day number of the leap second, 1..7, 8 bits
  int dt_lsf_s = 0;     // delta t_LSF, 8 bits signed, s
};

// One SV's almanac (subframe 5 pages 1-24, subframe 4 pages 2-5 and 7-10; Table 20-VI).
struct LnavAlmanacEntry {
  int sv_id = 0;                 // 1..32, the page's SV ID (20.3.3.5.1)
  double e = 0.0;                // 16 bits unsigned, 2^-21
  double toa_s = 0.0;            // seconds of week, 8 bits unsigned, 2^12 s
  double delta_i_rad = 0.0;      // i0 - 0.30 semicircles; 16 bits signed, 2^-19 semicircles
  double omega_dot_radps = 0.0;  // 16 bits signed, 2^-38 semicircles/s
  int health = 0;                // 8 bits (3 bits NAV data health, Table 20-VII; 5 bits signal
                                 // health, Table 20-VIII)
  double sqrt_a_sqrtm = 0.0;     // 24 bits unsigned, 2^-11 m^1/2
  double omega0_rad = 0.0;       // 24 bits signed, 2^-23 semicircles
  double omega_rad = 0.0;        // 24 bits signed, 2^-23 semicircles
  double m0_rad = 0.0;           // 24 bits signed, 2^-23 semicircles
  double af0_s = 0.0;            // 11 bits signed, 2^-20 s
  double af1_sps = 0.0;          // 11 bits signed, 2^-38 s/s
  // Subframe 4 page 25 (20.3.3.5.1.4): A-S flag and 3-bit SV configuration code
  // (1 = Block II/IIA/IIR capabilities, 2 = IIR-M, 3 = IIF, 4 = GPS III).
  int anti_spoof_flag = 0;
  int sv_config = 1;
};

// The subcommutated rest of subframes 4 and 5.
struct LnavAlmanac {
  // Almanac of the constellation, any order. A page whose SV has no entry here is sent as a
  // dummy SV page (SV ID 0, 20.3.3.5.1.1), and the SV's health in page 25 is 111111.
  std::span<const LnavAlmanacEntry> entries;
  double toa_s = 0.0;  // almanac reference time for subframe 5 page 25
  int week = 0;        // full week of toa; WNa is sent modulo 256
  // Subframe 4 page 17 (20.3.3.5.1.8): up to 22 ASCII characters, padded with spaces.
  std::string_view special_message;
};

// The words of subframe `subframe_id` (1..5) whose HOW carries `tow_count_next` (the 17-bit
// TOW count of the next subframe's start, 6 s units). Subframes 1-3 come from `eph`; for
// subframes 4 and 5, `page` (1..25) selects the page: page 18 of subframe 4 from `iono_utc`,
// the almanac pages and pages 25 from `almanac`, page 17 of subframe 4 the special message,
// page 13 an NMCT with no valid ERDs, and the reserved pages a valid page with data ID 01,
// the page's SV ID (Table 20-V) and alternating ones and zeros. `eph` always supplies the
// TLM/HOW flags of the transmitting SV. Reserved bits inside data pages and subframe 1
// (words 4-7) are zero, as in the reserved bits of the ZED-F9P capture.
LnavSubframe lnav_subframe(int subframe_id, std::uint32_t tow_count_next, const LnavEphemeris& eph,
                           const LnavIonoUtc& iono_utc, int page, const LnavAlmanac& almanac = {});

// Which subframe and which page of subframes 4/5 a satellite transmits in the subframe whose
// HOW carries `tow_count_next`: subframes repeat every 30 s from the start of the week, pages
// every 12.5 min (20.3.4.1).
int lnav_subframe_id_for(std::uint32_t tow_count_next);
int lnav_page_for(std::uint32_t tow_count_next);

// True when every word passes the parity check of Table 20-XIV with its bits 31..30 as
// D29*, D30* (bits 29..6 complemented first when bit 30 is set, as gpsd does), word 1 carries
// the preamble, bit 31 xor bit 30 of each word equals D29 xor D30 of the word before (both
// forms keep that invariant), and words 2 and 10 end with D29 = D30 as their t bits require.
// Accepts the u-blox form and the transmitted form alike.
bool lnav_parity_ok(const LnavSubframe& words);

// The same subframe as the satellite transmitted it: data bits complemented where D30* = 1,
// bits 31..30 = the transmitted D29*, D30* (the form gpsd's raw interpreter also accepts).
LnavSubframe lnav_as_transmitted(const LnavSubframe& words);

// TLM and HOW fields of any subframe (no parity check).
struct LnavTlmHow {
  int tlm_message = 0;
  int integrity_status_flag = 0;
  std::uint32_t tow_count = 0;  // of the next subframe's start
  int alert_flag = 0;
  int anti_spoof_flag = 0;
  int subframe_id = 0;
};
LnavTlmHow decode_tlm_how(const LnavSubframe& words);

// Subframes 1, 2 and 3 back to the ephemeris (TLM/HOW flags from subframe 1). nullopt when a
// subframe fails lnav_parity_ok(), the subframe IDs are not 1, 2, 3, or the IODEs of
// subframes 2 and 3 differ from each other or from the 8 LSBs of the IODC (a data set
// cutover, 20.3.4.4). The 10-bit week is resolved to the full week nearest to
// `reference_week`. sv_id is left 0.
std::optional<LnavEphemeris> decode_ephemeris(const LnavSubframe& sf1, const LnavSubframe& sf2,
                                              const LnavSubframe& sf3, int reference_week = 2200);

// Subframe 4 page 18 back to ionosphere/UTC parameters; the 8-bit weeks are resolved to the
// full weeks nearest to `reference_week`. nullopt unless it is a parity-correct subframe 4
// with SV ID 56.
std::optional<LnavIonoUtc> decode_iono_utc(const LnavSubframe& words, int reference_week = 2200);

// An almanac page (SV ID 1..32 in subframe 4 or 5) back to its entry (A-S flag and
// configuration left at their defaults). nullopt for other pages, dummy pages, bad parity.
std::optional<LnavAlmanacEntry> decode_almanac(const LnavSubframe& words);

// Subframe 4 page 17 back to its 22 characters. nullopt for other pages, bad parity.
std::optional<std::string> decode_special_message(const LnavSubframe& words);

// Data ID and SV ID (page ID) of a subframe 4 or 5 page (20.3.3.5.1.1).
struct LnavPageId {
  int data_id = 0;
  int sv_id = 0;
};
LnavPageId decode_page_id(const LnavSubframe& words);

// URA index of a URA in metres (the smallest N whose upper bound in 20.3.3.3.1.3 holds it;
// 15 above 6144 m or for NaN), and the nominal URA of an index (2^(1+N/2) m for N <= 6,
// 2^(N-2) m for 6 < N < 15; 15 gives 6144 m).
int lnav_ura_index(double ura_m);
double lnav_ura_m(int ura_index);

// A simple almanac entry from an ephemeris, referred to `toa_s` of week `toa_week`: the
// elements propagated from toe to toa (M0 by the corrected mean motion, Omega0 by
// Omega_dot, i by IDOT), the clock from toc to toa, the 6-bit SV health expanded to the
// 8-bit form (NAV data "all data bad" when its summary bit is set).
LnavAlmanacEntry lnav_almanac_from_ephemeris(const LnavEphemeris& eph, double toa_s, int toa_week);

}  // namespace navemu::lnav
