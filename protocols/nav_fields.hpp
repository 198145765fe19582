#pragma once
// Fixed-point fields of the broadcast navigation messages with a GPS-style layout: GPS/QZSS
// LNAV (IS-GPS-200 20.3.3), Galileo I/NAV (OS SIS ICD 2.0 4.3.5, 5.1) and BeiDou D1/D2
// (BDS-SIS-ICD-B1I 3.0 5.2.4). A field's bits travel in a std::uint64_t (two's complement in
// `bits` for signed fields). Encoding rounds to the LSB and then: clamps (every measured
// quantity; NaN gives 0), wraps (counters and identifiers: low_bits), or reduces to
// [-pi, pi) first (full angles, q_angle); times of week clamp to [0, 604800) and the field.
// Angles are radians here and semicircles on the wire, with the pi these ICDs fix.

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace navemu::navfield {

// pi for semicircle conversions (IS-GPS-200 20.3.3.4.3.1; OS SIS ICD 5.1.1; BDS ICD 5.2.4).
inline constexpr double kSemicirclePi = 3.1415926535898;

inline std::uint64_t mask(int bits) { return bits >= 64 ? ~0ULL : (1ULL << bits) - 1; }

// An integer clamped to an unsigned field.
inline std::uint64_t field_u(long long v, int bits) {
  return static_cast<std::uint64_t>(std::clamp(v, 0LL, static_cast<long long>(mask(std::min(bits, 63)))));
}

// The low bits of a counter or identifier (weeks, issues of data): these wrap.
inline std::uint64_t low_bits(long long v, int bits) {
  const long long m = 1LL << bits;
  return static_cast<std::uint64_t>(((v % m) + m) % m);
}

// x / lsb rounded, clamped to `bits` (two's complement when is_signed), NaN -> 0.
inline std::uint64_t quantise_lsb(double x, double lsb, int bits, bool is_signed) {
  const double lo = is_signed ? -std::ldexp(1.0, bits - 1) : 0.0;
  const double hi = is_signed ? std::ldexp(1.0, bits - 1) - 1.0 : std::ldexp(1.0, bits) - 1.0;
  double q = std::nearbyint(x / lsb);
  if (std::isnan(q)) q = 0.0;
  q = std::clamp(q, lo, hi);
  return static_cast<std::uint64_t>(static_cast<long long>(q)) & mask(bits);
}
// The same with an LSB of 2^lsb_exp.
inline std::uint64_t q_signed(double x, int lsb_exp, int bits) {
  return quantise_lsb(x, std::ldexp(1.0, lsb_exp), bits, true);
}
inline std::uint64_t q_unsigned(double x, int lsb_exp, int bits) {
  return quantise_lsb(x, std::ldexp(1.0, lsb_exp), bits, false);
}
// A rate or small angle in radians as semicircles.
inline std::uint64_t q_sc(double rad, int lsb_exp, int bits) { return q_signed(rad / kSemicirclePi, lsb_exp, bits); }
// A full angle in radians as semicircles, reduced to [-1, 1) semicircles first: an angle has
// no range to clamp to, and +pi is -pi.
inline std::uint64_t q_angle(double rad, int lsb_exp, int bits) {
  double sc = rad / kSemicirclePi;
  if (!std::isfinite(sc)) sc = 0.0;
  sc -= 2.0 * std::floor((sc + 1.0) / 2.0);
  const long long full = 1LL << bits;
  long long q = std::llround(std::ldexp(sc, -lsb_exp));
  if (q >= full / 2) q -= full;  // rounding up to +1 semicircle wraps to -1
  if (q < -full / 2) q += full;
  return static_cast<std::uint64_t>(q) & mask(bits);
}
// A time of week in units of `unit_s`, within [0, 604800) and the field.
inline std::uint64_t q_time_units(double t_s, double unit_s, int bits) {
  const double max_units = std::ceil(604800.0 / unit_s) - 1.0;
  double q = std::nearbyint(t_s / unit_s);
  if (std::isnan(q)) q = 0.0;
  return static_cast<std::uint64_t>(std::clamp(q, 0.0, std::min(max_units, std::ldexp(1.0, bits) - 1.0)));
}
// The same in units of 2^lsb_exp s.
inline std::uint64_t q_time(double t_s, int lsb_exp, int bits) {
  return q_time_units(t_s, std::ldexp(1.0, lsb_exp), bits);
}

// Decoding: a field's bits back to numbers.
inline std::int64_t sign_extend(std::uint64_t v, int bits) {
  const auto x = static_cast<std::int64_t>(v & mask(bits));
  return (x & (std::int64_t{1} << (bits - 1))) != 0 ? x - (std::int64_t{1} << bits) : x;
}
inline double d_signed(std::uint64_t v, int bits, int lsb_exp) {
  return std::ldexp(static_cast<double>(sign_extend(v, bits)), lsb_exp);
}
inline double d_unsigned(std::uint64_t v, int lsb_exp) { return std::ldexp(static_cast<double>(v), lsb_exp); }
inline double d_sc(std::uint64_t v, int bits, int lsb_exp) { return d_signed(v, bits, lsb_exp) * kSemicirclePi; }

}  // namespace navemu::navfield
