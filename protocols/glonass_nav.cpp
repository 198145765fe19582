// GLONASS L1OF/L2OF navigation strings: encoder, Hamming code and decoders (GLONASS ICD
// edition 5.1, section 4). See glonass_nav.hpp for the word format.
#include "protocols/glonass_nav.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <numbers>

namespace navemu::gnav {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kKm = 1000.0;
constexpr std::int64_t kGlonassMinusUtc_ns = std::int64_t{kGlonassMinusUtc_s} * kNsPerS;
// Days from the GPS epoch (1980-01-06) to 1996-01-01, the start of the first four-year
// interval N_4 = 1 (4.5, N_4): 5 days back to 1980-01-01, then 16 years = 4 x 1461 days.
constexpr std::int64_t kDays1996 = 4 * 1461 - 5;

// ---- bits: ICD bit b (85..1) is bit 31 - (85 - b) % 32 of word (85 - b) / 32 ----------------

std::uint32_t get_bit(const GnavString& w, int b) {
  const int pos = 85 - b;
  return (w[static_cast<std::size_t>(pos / 32)] >> (31 - pos % 32)) & 1u;
}
void set_bit(GnavString& w, int b, std::uint32_t v) {
  const int pos = 85 - b;
  const std::uint32_t mask = 1u << (31 - pos % 32);
  auto& word = w[static_cast<std::size_t>(pos / 32)];
  word = (v & 1u) != 0 ? (word | mask) : (word & ~mask);
}
// A field of `bits` bits whose most significant bit is ICD bit `msb`.
void put(GnavString& w, int msb, int bits, std::uint64_t v) {
  for (int i = 0; i < bits; ++i)
    set_bit(w, msb - i, static_cast<std::uint32_t>((v >> (bits - 1 - i)) & 1u));
}
std::uint64_t get(const GnavString& w, int msb, int bits) {
  std::uint64_t v = 0;
  for (int i = 0; i < bits; ++i) v = (v << 1) | get_bit(w, msb - i);
  return v;
}

// ---- quantisation -------------------------------------------------------------------------

std::uint32_t field_u(long long v, int bits) {
  return static_cast<std::uint32_t>(std::clamp(v, 0LL, (1LL << bits) - 1));
}
// x / lsb rounded to a magnitude of bits - 1 bits, sign-magnitude (4.4): sign bit = the sign
// of x (so -0.0 stays a negative zero), magnitude clamped, NaN -> +0.
std::uint64_t q_sm(double x, double lsb, int bits) {
  if (std::isnan(x)) return 0;
  const double max_mag = std::ldexp(1.0, bits - 1) - 1.0;
  const double mag = std::min(std::nearbyint(std::fabs(x) / lsb), max_mag);
  const std::uint64_t sign = std::signbit(x) ? 1u : 0u;
  return (sign << (bits - 1)) | static_cast<std::uint64_t>(mag);
}
double d_sm(std::uint64_t v, double lsb, int bits) {
  const double mag = static_cast<double>(v & ((std::uint64_t{1} << (bits - 1)) - 1)) * lsb;
  return ((v >> (bits - 1)) & 1u) != 0 ? -mag : mag;
}
std::uint64_t q_u(double x, double lsb, int bits) {
  if (std::isnan(x)) return 0;
  const double q = std::clamp(std::nearbyint(x / lsb), 0.0, std::ldexp(1.0, bits) - 1.0);
  return static_cast<std::uint64_t>(q);
}
double p2(int e) { return std::ldexp(1.0, e); }

// ---- time ---------------------------------------------------------------------------------

// GLONASS time as nanoseconds since the GPS epoch read on the GLONASS clock.
std::int64_t glonass_ns(GpsTime t, int leap_seconds) {
  return t.ns - std::int64_t{leap_seconds} * kNsPerS + kGlonassMinusUtc_ns;
}
std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}
constexpr std::int64_t kDay_ns = kSecondsPerDay * kNsPerS;
// The GPS time of a GLONASS time given as glonass_ns() gives it.
GpsTime gps_of_glonass(std::int64_t glonass_ns_value, int leap_seconds) {
  return GpsTime{glonass_ns_value + std::int64_t{leap_seconds} * kNsPerS - kGlonassMinusUtc_ns};
}

// ---- Hamming code (4.7) -------------------------------------------------------------------

// The syndrome of bits 85..9: bit b carries Hamming position h, the b - 8th position that is
// not a power of two (3, 5, 6, 7, 9, ...); check bit beta_i (ICD bit i, i = 1..7) is the
// parity of the bits whose position has bit i - 1 set. This is the ICD's table of beta_1 ..
// beta_7; beta_8 (bit 8) makes the parity of bits 1..85 even.
std::uint32_t data_syndrome(const GnavString& w) {
  std::uint32_t syn = 0;
  std::uint32_t h = 3;
  for (int b = 9; b <= 85; ++b, ++h) {
    while ((h & (h - 1)) == 0) ++h;
    if (get_bit(w, b) != 0) syn ^= h;
  }
  return syn;
}
void put_hamming(GnavString& w) {
  const std::uint32_t syn = data_syndrome(w);
  std::uint32_t parity = 0;
  for (int b = 9; b <= 85; ++b) parity ^= get_bit(w, b);
  for (int i = 1; i <= 7; ++i) {
    const std::uint32_t beta = (syn >> (i - 1)) & 1u;
    set_bit(w, i, beta);
    parity ^= beta;
  }
  set_bit(w, 8, parity);
}

// ---- strings ------------------------------------------------------------------------------

std::uint32_t tk_field(double frame_time_s) {
  // UTC seconds of week -> GLONASS time of day; hours 5 bits, minutes 6 bits, 30 s 1 bit (4.4).
  double tod = std::isnan(frame_time_s) ? 0.0 : std::fmod(frame_time_s + kGlonassMinusUtc_s, 86400.0);
  if (tod < 0.0) tod += 86400.0;
  const auto units = static_cast<long long>(std::floor(tod / 30.0));  // 0..2879
  const long long hours = units / 120;
  const long long minutes = (units % 120) / 2;
  return (field_u(hours, 5) << 7) | (field_u(minutes, 6) << 1) | static_cast<std::uint32_t>(units % 2);
}

// tb: 7 bits, 15 min units of the GLONASS day of tb (4.4).
std::uint32_t tb_field(GpsTime tb, int leap_seconds) {
  const std::int64_t g = glonass_ns(tb, leap_seconds);
  const std::int64_t tod_ns = g - floor_div(g, kDay_ns) * kDay_ns;
  return field_u(std::llround(static_cast<double>(tod_ns) * 1e-9 / 900.0), 7);
}

void put_axis(GnavString& w, const GlonassEphemeris& e, Eigen::Index axis) {
  // x' 64..41 (24 bits, 2^-20 km/s), x'' 40..36 (5 bits, 2^-30 km/s^2), x 35..9 (27 bits,
  // 2^-11 km), Table 4.5; likewise y (string 2), z (string 3).
  put(w, 64, 24, q_sm(e.v_pz90_mps[axis], p2(-20) * kKm, 24));
  put(w, 40, 5, q_sm(e.a_pz90_mps2[axis], p2(-30) * kKm, 5));
  put(w, 35, 27, q_sm(e.p_pz90_m[axis], p2(-11) * kKm, 27));
}

void put_immediate(GnavString& w, int string, const GlonassEphemeris& e, const GnavImmediateFlags& f,
                   int leap_seconds) {
  const std::uint32_t tb = tb_field(e.tb, leap_seconds);
  switch (string) {
    case 1:  // bits 80..79 reserved; P1 78..77; tk 76..65
      put(w, 78, 2, field_u(f.p1, 2));
      put(w, 76, 12, tk_field(f.frame_time_s.value_or(e.frame_time_s)));
      put_axis(w, e, 0);
      break;
    case 2:  // B_n 80..78; P2 77; tb 76..70; bits 69..65 reserved
      put(w, 80, 3, ((e.health != 0 ? 4u : 0u) | field_u(f.b_n_lsbs, 2)));
      put(w, 77, 1, f.p2 ? field_u(*f.p2, 1) : (tb & 1u));
      put(w, 76, 7, tb);
      put_axis(w, e, 1);
      break;
    case 3:  // P3 80; gamma_n 79..69 (11 bits, 2^-40); bit 68 reserved; P 67..66; l_n 65
      put(w, 80, 1, field_u(f.p3, 1));
      put(w, 79, 11, q_sm(e.gamma_n, p2(-40), 11));
      put(w, 67, 2, field_u(f.p, 2));
      put(w, 65, 1, field_u(f.l_n, 1));
      put_axis(w, e, 2);
      break;
    default: {  // 4: tau_n 80..59 (22 bits, 2^-30 s); delta tau_n 58..54 (5 bits, 2^-30 s);
                // E_n 53..49; reserved 48..35; P4 34; F_T 33..30; reserved 29..27;
                // N_T 26..16; n 15..11; M 10..9
      const std::int64_t g = glonass_ns(e.tb, leap_seconds);
      const std::int64_t d96 = floor_div(g, kDay_ns) - kDays1996;
      const std::int64_t nt = d96 - floor_div(d96, 1461) * 1461 + 1;
      put(w, 80, 22, q_sm(e.tau_n_s, p2(-30), 22));
      put(w, 58, 5, q_sm(f.delta_tau_n_s, p2(-30), 5));
      put(w, 53, 5, q_u(e.age_days, 1.0, 5));
      put(w, 48, 14, f.reserved_s4 & 0x3FFFu);
      put(w, 34, 1, field_u(f.p4, 1));
      put(w, 33, 4, field_u(f.f_t, 4));
      put(w, 26, 11, field_u(nt, 11));
      put(w, 15, 5, field_u(e.sat.number(), 5));
      put(w, 10, 2, field_u(f.m, 2));
      break;
    }
  }
}

void put_system(GnavString& w, const GnavSystemData& s, int l_n) {
  // String 5: N_A 80..70; tau_c 69..38 (32 bits, 2^-31 s); bit 37 reserved; N_4 36..32;
  // tau_GPS 31..10 (22 bits, 2^-30 s); l_n 9 (Table 4.9).
  put(w, 80, 11, field_u(s.n_a, 11));
  put(w, 69, 32, q_sm(s.tau_c_s, p2(-31), 32));
  put(w, 36, 5, field_u(s.n4, 5));
  put(w, 31, 22, q_sm(s.tau_gps_s, p2(-30), 22));
  put(w, 9, 1, field_u(l_n, 1));
}

const GnavAlmanacEntry* find_slot(std::span<const GnavAlmanacEntry> almanac, int slot) {
  for (const auto& a : almanac)
    if (a.slot == slot) return &a;
  return nullptr;
}

// h_A: 0..24 as is, -7..-1 as 25..31 (4.5, Table 4.10).
std::uint32_t h_a_field(int k) { return k < 0 ? field_u(k + 32, 5) : field_u(k, 5); }
int h_a_value(std::uint32_t v) { return v >= 25 ? static_cast<int>(v) - 32 : static_cast<int>(v); }

void put_almanac_first(GnavString& w, const GnavAlmanacEntry& a) {
  // Strings 6, 8, ..., 14: C_n 80; M_n 79..78; n_A 77..73; tau_A 72..63 (10 bits, 2^-18 s);
  // lambda_A 62..42 (21 bits, 2^-20 sc); delta i_A 41..24 (18 bits, 2^-20 sc);
  // epsilon_A 23..9 (15 bits, 2^-20) (Table 4.9).
  put(w, 80, 1, field_u(a.c_n, 1));
  put(w, 79, 2, field_u(a.m_n, 2));
  put(w, 77, 5, field_u(a.slot, 5));
  put(w, 72, 10, q_sm(a.tau_a_s, p2(-18), 10));
  put(w, 62, 21, q_sm(a.lambda_rad / kPi, p2(-20), 21));
  put(w, 41, 18, q_sm(a.delta_i_rad / kPi, p2(-20), 18));
  put(w, 23, 15, q_u(a.epsilon, p2(-20), 15));
}
void put_almanac_second(GnavString& w, const GnavAlmanacEntry& a) {
  // Strings 7, 9, ..., 15: omega_A 80..65 (16 bits, 2^-15 sc); t_lambda 64..44 (21 bits,
  // 2^-5 s); delta T_A 43..22 (22 bits, 2^-9 s); delta T dot 21..15 (7 bits, 2^-14 s);
  // H_A 14..10; l_n 9 (of the transmitting satellite).
  put(w, 80, 16, q_sm(a.omega_rad / kPi, p2(-15), 16));
  put(w, 64, 21, q_u(a.t_lambda_s, p2(-5), 21));
  put(w, 43, 22, q_sm(a.delta_t_s, p2(-9), 22));
  put(w, 21, 7, q_sm(a.delta_t_dot_s, p2(-14), 7));
  put(w, 14, 5, h_a_field(a.h_a));
}

bool string_ok(const GnavString& w, int m) {
  return glonass_hamming_ok(w) && glonass_string_number(w) == m;
}

}  // namespace

// ---- schedule (4.3) -----------------------------------------------------------------------

GnavSlot glonass_slot(GpsTime t, int leap_seconds) {
  const std::int64_t g = glonass_ns(t, leap_seconds);
  const std::int64_t s = floor_div(g, kNsPerS);
  const std::int64_t tod = s - floor_div(s, kSecondsPerDay) * kSecondsPerDay;
  const std::int64_t tow = s - floor_div(s, kSecondsPerWeek) * kSecondsPerWeek;
  GnavSlot out;
  out.superframe = static_cast<int>(tow / 150) + 1;
  out.frame = static_cast<int>((tod % 150) / 30) + 1;
  out.string = static_cast<int>((tod % 30) / 2) + 1;
  const std::int64_t frame_start_s = s - tod % 30;
  const GpsTime start = gps_of_glonass(frame_start_s * kNsPerS, leap_seconds);
  const std::int64_t utc_s = floor_div(start.ns, kNsPerS) - leap_seconds;
  out.frame_time_s = static_cast<double>(utc_s - floor_div(utc_s, kSecondsPerWeek) * kSecondsPerWeek);
  return out;
}

GnavDay glonass_day(GpsTime t, int leap_seconds) {
  const std::int64_t d96 = floor_div(glonass_ns(t, leap_seconds), kDay_ns) - kDays1996;
  const std::int64_t q = floor_div(d96, 1461);
  return GnavDay{static_cast<int>(q + 1), static_cast<int>(d96 - q * 1461 + 1)};
}

std::uint32_t ublox_word4(int superframe, int frame) {
  return (field_u(superframe, 16) << 16) | field_u(frame, 8);
}

// ---- encoder ------------------------------------------------------------------------------

GnavString glonass_string(int frame, int string, const GlonassEphemeris& eph, const GnavImmediateFlags& flags,
                          int leap_seconds, const GnavSystemData& sys, std::span<const GnavAlmanacEntry> almanac,
                          int superframe) {
  frame = std::clamp(frame, 1, kFramesPerSuperframe);
  string = std::clamp(string, 1, kStringsPerFrame);
  GnavString w{};
  put(w, 84, 4, static_cast<std::uint32_t>(string));  // bit 85, the idle chip, stays 0
  if (string <= 4) {
    put_immediate(w, string, eph, flags, leap_seconds);
  } else if (string == 5) {
    put_system(w, sys, flags.l_n);
  } else if (frame == 5 && string == 14) {
    // B1 80..70 (11 bits, 2^-10 s); B2 69..60 (10 bits, 2^-16 s/day); KP 59..58; 57..9 reserved.
    put(w, 80, 11, q_sm(sys.b1_s, p2(-10), 11));
    put(w, 69, 10, q_sm(sys.b2_spd, p2(-16), 10));
    put(w, 59, 2, field_u(sys.kp, 2));
    put(w, 57, 49, sys.reserved_f5s14 & ((std::uint64_t{1} << 49) - 1));
  } else if (frame == 5 && string == 15) {
    // Bits 80..10 reserved; l_n 9.
    put(w, 80, 7, sys.reserved_f5s15[0] & 0x7Fu);
    put(w, 73, 32, sys.reserved_f5s15[1]);
    put(w, 41, 32, sys.reserved_f5s15[2]);
    put(w, 9, 1, field_u(flags.l_n, 1));
  } else {
    const int slot = 5 * (frame - 1) + (string - 4) / 2;
    const GnavAlmanacEntry* a = find_slot(almanac, slot);
    const bool odd_string = string % 2 == 1;  // 7, 9, ...: the second string of a slot
    if (a != nullptr) {
      if (odd_string)
        put_almanac_second(w, *a);
      else
        put_almanac_first(w, *a);
    }
    if (odd_string) put(w, 9, 1, field_u(flags.l_n, 1));
  }
  put_hamming(w);
  w[3] = ublox_word4(superframe, frame);
  return w;
}

GnavString glonass_string(int frame, int string, const GnavEphemeris& eph, int leap_seconds,
                          const GnavSystemData& sys, std::span<const GnavAlmanacEntry> almanac,
                          int superframe) {
  return glonass_string(frame, string, eph.eph, eph.flags, leap_seconds, sys, almanac, superframe);
}

// ---- Hamming check (4.7) ------------------------------------------------------------------

GnavHammingResult glonass_hamming(const GnavString& words) {
  std::uint32_t syn = data_syndrome(words);
  for (int i = 1; i <= 7; ++i) syn ^= get_bit(words, i) << (i - 1);
  std::uint32_t sigma = 0;
  for (int b = 1; b <= 85; ++b) sigma ^= get_bit(words, b);
  const int ones = std::popcount(syn);
  // 4.7: correct when every checksum is 0, or one of C1..C7 and C_sigma are 1 (a check bit);
  // two or more of C1..C7 with C_sigma 1 locate a data bit; anything else (C1..C7 with
  // C_sigma 0, or C_sigma alone, as after a flipped beta8) is two or more errors.
  if (sigma == 0 || ones == 0) return {syn == 0 && sigma == 0 ? GnavHamming::kOk : GnavHamming::kBad, 0};
  if (ones == 1) return {GnavHamming::kCheckBitError, std::countr_zero(syn) + 1};
  // Hamming position syn is ICD bit syn + 8 - (the number of powers of two up to syn), the
  // bit that 4.7 b) names for correction.
  const int k = static_cast<int>(syn);
  const int bit = k + 7 - static_cast<int>(std::bit_width(syn) - 1);
  if (bit > 85) return {GnavHamming::kBad, 0};
  return {GnavHamming::kCorrectable, bit};
}

bool glonass_hamming_ok(const GnavString& words) {
  return get_bit(words, 85) == 0 && glonass_hamming(words).status == GnavHamming::kOk;
}

std::optional<GnavString> glonass_correct(const GnavString& words) {
  const GnavHammingResult r = glonass_hamming(words);
  if (r.status == GnavHamming::kBad) return std::nullopt;
  GnavString out = words;
  if (r.status != GnavHamming::kOk) set_bit(out, r.bit, get_bit(out, r.bit) ^ 1u);
  return out;
}

int glonass_string_number(const GnavString& words) { return static_cast<int>(get(words, 84, 4)); }

GnavUbloxTag decode_ublox_tag(const GnavString& words) {
  return GnavUbloxTag{static_cast<int>(words[3] >> 16), static_cast<int>(words[3] & 0xFFu)};
}

// ---- decoders -----------------------------------------------------------------------------

std::optional<GnavEphemeris> decode_ephemeris(const GnavString& s1, const GnavString& s2,
                                              const GnavString& s3, const GnavString& s4,
                                              int leap_seconds, GpsTime reference,
                                              std::optional<int> n4) {
  if (!string_ok(s1, 1) || !string_ok(s2, 2) || !string_ok(s3, 3) || !string_ok(s4, 4))
    return std::nullopt;
  GnavEphemeris out;
  GlonassEphemeris& e = out.eph;
  GnavImmediateFlags& f = out.flags;
  const std::array<const GnavString*, 3> axes = {&s1, &s2, &s3};
  for (Eigen::Index i = 0; i < 3; ++i) {
    const GnavString& w = *axes[static_cast<std::size_t>(i)];
    e.v_pz90_mps[i] = d_sm(get(w, 64, 24), p2(-20) * kKm, 24);
    e.a_pz90_mps2[i] = d_sm(get(w, 40, 5), p2(-30) * kKm, 5);
    e.p_pz90_m[i] = d_sm(get(w, 35, 27), p2(-11) * kKm, 27);
  }
  f.p1 = static_cast<int>(get(s1, 78, 2));
  const auto tk = static_cast<int>(get(s1, 76, 12));
  const auto b_n = static_cast<int>(get(s2, 80, 3));
  e.health = b_n >> 2;
  f.b_n_lsbs = b_n & 3;
  f.p2 = static_cast<int>(get(s2, 77, 1));
  const auto tb = static_cast<std::int64_t>(get(s2, 76, 7));
  f.p3 = static_cast<int>(get(s3, 80, 1));
  e.gamma_n = d_sm(get(s3, 79, 11), p2(-40), 11);
  f.p = static_cast<int>(get(s3, 67, 2));
  f.l_n = static_cast<int>(get(s3, 65, 1));
  e.tau_n_s = d_sm(get(s4, 80, 22), p2(-30), 22);
  f.delta_tau_n_s = d_sm(get(s4, 58, 5), p2(-30), 5);
  e.age_days = static_cast<double>(get(s4, 53, 5));
  f.reserved_s4 = static_cast<std::uint32_t>(get(s4, 48, 14));
  f.p4 = static_cast<int>(get(s4, 34, 1));
  f.f_t = static_cast<int>(get(s4, 33, 4));
  const auto nt = static_cast<std::int64_t>(get(s4, 26, 11));
  e.sat = SatId(GnssSystem::kGlonass, static_cast<int>(get(s4, 15, 5)));
  f.m = static_cast<int>(get(s4, 10, 2));

  // The GLONASS day (days since the GPS epoch) of day N_T.
  std::int64_t day = 0;
  if (nt < 1 || nt > 1461) return std::nullopt;
  if (n4) {
    if (*n4 < 1 || *n4 > 31) return std::nullopt;
    day = kDays1996 + std::int64_t{*n4 - 1} * 1461 + nt - 1;
  } else {
    const std::int64_t ref_day = floor_div(glonass_ns(reference, leap_seconds), kDay_ns);
    const std::int64_t base = kDays1996 + floor_div(ref_day - kDays1996, 1461) * 1461 + nt - 1;
    day = base;
    for (const std::int64_t c : {base - 1461, base + 1461})
      if (std::llabs(c - ref_day) < std::llabs(day - ref_day)) day = c;
  }
  e.tb = gps_of_glonass(day * kDay_ns + tb * 900 * kNsPerS, leap_seconds);
  const std::int64_t tk_s = (tk >> 7) * 3600 + ((tk >> 1) & 0x3F) * 60 + (tk & 1) * 30;
  // tk is a time of day: the one nearest tb (a frame may precede tb across midnight).
  std::int64_t tk_ns = day * kDay_ns + tk_s * kNsPerS;
  const std::int64_t tb_ns = day * kDay_ns + tb * 900 * kNsPerS;
  if (tk_ns - tb_ns > kDay_ns / 2) tk_ns -= kDay_ns;
  if (tb_ns - tk_ns > kDay_ns / 2) tk_ns += kDay_ns;
  const GpsTime frame_start = gps_of_glonass(tk_ns, leap_seconds);
  const std::int64_t utc_s = floor_div(frame_start.ns, kNsPerS) - leap_seconds;
  e.frame_time_s =
      static_cast<double>(utc_s - floor_div(utc_s, kSecondsPerWeek) * kSecondsPerWeek);
  return out;
}

std::optional<GnavSystemData> decode_system_data(const GnavString& s5) {
  if (!string_ok(s5, 5)) return std::nullopt;
  GnavSystemData s;
  s.n_a = static_cast<int>(get(s5, 80, 11));
  s.tau_c_s = d_sm(get(s5, 69, 32), p2(-31), 32);
  s.n4 = static_cast<int>(get(s5, 36, 5));
  s.tau_gps_s = d_sm(get(s5, 31, 22), p2(-30), 22);
  return s;
}

std::optional<GnavSystemData> decode_system_data(const GnavString& s5, const GnavString& f5s14,
                                                 const GnavString& f5s15) {
  auto s = decode_system_data(s5);
  if (!s || !string_ok(f5s14, 14) || !string_ok(f5s15, 15)) return std::nullopt;
  s->b1_s = d_sm(get(f5s14, 80, 11), p2(-10), 11);
  s->b2_spd = d_sm(get(f5s14, 69, 10), p2(-16), 10);
  s->kp = static_cast<int>(get(f5s14, 59, 2));
  s->reserved_f5s14 = get(f5s14, 57, 49);
  s->reserved_f5s15 = {static_cast<std::uint32_t>(get(f5s15, 80, 7)),
                       static_cast<std::uint32_t>(get(f5s15, 73, 32)),
                       static_cast<std::uint32_t>(get(f5s15, 41, 32))};
  return s;
}

std::optional<int> decode_l_n(const GnavString& words) {
  if (!glonass_hamming_ok(words)) return std::nullopt;
  const int m = glonass_string_number(words);
  if (m == 3) return static_cast<int>(get(words, 65, 1));
  if (m >= 5 && m % 2 == 1) return static_cast<int>(get(words, 9, 1));
  return std::nullopt;
}

std::optional<GnavAlmanacEntry> decode_almanac(const GnavString& first, const GnavString& second) {
  const int m = glonass_string_number(first);
  if (m < 6 || m > 14 || m % 2 != 0 || !string_ok(first, m) || !string_ok(second, m + 1))
    return std::nullopt;
  GnavAlmanacEntry a;
  a.slot = static_cast<int>(get(first, 77, 5));
  if (a.slot == 0) return std::nullopt;
  a.c_n = static_cast<int>(get(first, 80, 1));
  a.m_n = static_cast<int>(get(first, 79, 2));
  a.tau_a_s = d_sm(get(first, 72, 10), p2(-18), 10);
  a.lambda_rad = d_sm(get(first, 62, 21), p2(-20), 21) * kPi;
  a.delta_i_rad = d_sm(get(first, 41, 18), p2(-20), 18) * kPi;
  a.epsilon = static_cast<double>(get(first, 23, 15)) * p2(-20);
  a.omega_rad = d_sm(get(second, 80, 16), p2(-15), 16) * kPi;
  a.t_lambda_s = static_cast<double>(get(second, 64, 21)) * p2(-5);
  a.delta_t_s = d_sm(get(second, 43, 22), p2(-9), 22);
  a.delta_t_dot_s = d_sm(get(second, 21, 7), p2(-14), 7);
  a.h_a = h_a_value(static_cast<std::uint32_t>(get(second, 14, 5)));
  return a;
}

}  // namespace navemu::gnav
