// BeiDou B1I D1/D2 subframe encoders and decoders (BDS-SIS-ICD-B1I 3.0 section 5). See
// beidou_nav.hpp for the word format.
#include "protocols/beidou_nav.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "protocols/nav_fields.hpp"

namespace navemu::bdnav {
namespace {

constexpr int kInfoBits = 224;  // 26 + 9 x 22 information bits of a subframe
constexpr int kHeaderBits = 38;  // Pre 11, Rev 4, FraID 3, SOW 20 (5.2.3, 5.3.2)
constexpr std::uint32_t kSecondsPerWeekU = 604800;

// ---- BCH(15,11,1), g(X) = X^4 + X + 1 (5.1.3) -------------------------------------------------

// The 4 check bits of 11 information bits: the remainder of info * X^4 divided by g(X).
std::uint32_t bch4(std::uint32_t info11) {
  std::uint32_t r = (info11 & 0x7FFu) << 4;
  for (int i = 14; i >= 4; --i)
    if (((r >> i) & 1u) != 0) r ^= 0x13u << (i - 4);
  return r & 0xFu;
}

// Information bit `i` (0..223) of the stream: word and bit position in the u-blox word.
struct BitPos {
  std::size_t word;
  int bit;
};
constexpr BitPos bit_pos(int i) {
  if (i < 26) return {0, 29 - i};
  const int j = i - 26;
  return {static_cast<std::size_t>(1 + j / 22), 29 - j % 22};
}

// The check bits of each word computed over its information bits (which are already set).
BdsSubframe with_parity(BdsSubframe w) {
  w[0] = (w[0] & 0x3FFFFFF0u) | bch4(w[0] >> 4);
  for (std::size_t k = 1; k < 10; ++k) {
    const std::uint32_t i1 = (w[k] >> 19) & 0x7FFu;
    const std::uint32_t i2 = (w[k] >> 8) & 0x7FFu;
    w[k] = (i1 << 19) | (i2 << 8) | (bch4(i1) << 4) | bch4(i2);
  }
  return w;
}

class BitWriter {
 public:
  void put(std::uint64_t v, int bits) {
    for (int i = bits - 1; i >= 0 && pos_ < kInfoBits; --i, ++pos_) {
      const BitPos p = bit_pos(pos_);
      w_[p.word] |= static_cast<std::uint32_t>((v >> i) & 1u) << p.bit;
    }
  }
  void zeros(int bits) { pos_ = std::min(kInfoBits, pos_ + bits); }
  BdsSubframe finish() const { return with_parity(w_); }

 private:
  BdsSubframe w_{};
  int pos_ = 0;
};

class BitReader {
 public:
  explicit BitReader(const BdsSubframe& w, int start = 0) : w_(w), pos_(start) {}
  std::uint32_t get(int bits) {
    std::uint32_t v = 0;
    for (int i = 0; i < bits && pos_ < kInfoBits; ++i, ++pos_) {
      const BitPos p = bit_pos(pos_);
      v = (v << 1) | ((w_[p.word] >> p.bit) & 1u);
    }
    return v;
  }
  void skip(int bits) { pos_ = std::min(kInfoBits, pos_ + bits); }

 private:
  const BdsSubframe& w_;
  int pos_;
};

// ---- quantisation (protocols/nav_fields.hpp) ---------------------------------------------------

using namespace navfield;
// BeiDou's time offsets and group delays count in 0.1 ns (5.2.4.10, 5.2.4.19).
double d_01ns(std::uint64_t v, int bits) { return static_cast<double>(sign_extend(v, bits)) * 1e-10; }

// BDT second of week of a GPS time.
double bdt_tow(GpsTime t) { return to_week_tow(t.plus_s(-kGpsMinusBdt_s)).tow_s; }

// ---- the clock/ephemeris/ionosphere fields as raw integers, shared by D1 and D2 --------------

struct Raw {
  std::uint64_t sath1, aodc, urai, wn, toc, tgd1, tgd2, a0, a1, a2, aode;
  std::uint64_t alpha0, alpha1, alpha2, alpha3, beta0, beta1, beta2, beta3;
  std::uint64_t dn, cuc, m0, e, cus, crc, crs, sqrta, toe, i0, cic, omegadot, cis, idot, omega0,
      omega;
};

// Bits hi..lo of a field (the ICD splits some over words or D2 pages); field nullptr: reserved.
struct Slot {
  std::uint64_t Raw::*field;
  int hi, lo;
};
constexpr Slot full(std::uint64_t Raw::*f, int bits) { return {f, bits - 1, 0}; }
constexpr Slot reserved(int bits) { return {nullptr, bits - 1, 0}; }

// Field widths and scale factors: 5.2.4 (D1 subframes 1-3), the same in D2 (5.3.3).
Raw to_raw(const BeidouEphemeris& eph, const KlobucharCoefficients& iono, int week) {
  Raw r{};
  r.sath1 = field_u(eph.health, 1);
  r.aodc = low_bits(eph.aodc, 5);
  r.urai = static_cast<std::uint32_t>(bds_ura_index(eph.ura_m));
  r.wn = low_bits(week, 13);
  r.toc = q_time(bdt_tow(eph.toc), 3, 17);
  r.tgd1 = quantise_lsb(eph.tgd1_s, 1e-10, 10, true);  // 0.1 ns
  r.tgd2 = quantise_lsb(eph.tgd2_s, 1e-10, 10, true);
  r.alpha0 = q_signed(iono.alpha[0], -30, 8);
  r.alpha1 = q_signed(iono.alpha[1], -27, 8);
  r.alpha2 = q_signed(iono.alpha[2], -24, 8);
  r.alpha3 = q_signed(iono.alpha[3], -24, 8);
  r.beta0 = q_signed(iono.beta[0], 11, 8);
  r.beta1 = q_signed(iono.beta[1], 14, 8);
  r.beta2 = q_signed(iono.beta[2], 16, 8);
  r.beta3 = q_signed(iono.beta[3], 16, 8);
  r.a2 = q_signed(eph.af2_sps2, -66, 11);
  r.a0 = q_signed(eph.af0_s, -33, 24);
  r.a1 = q_signed(eph.af1_sps, -50, 22);
  r.aode = low_bits(eph.aode, 5);
  r.dn = q_sc(eph.delta_n_radps, -43, 16);
  r.cuc = q_signed(eph.cuc_rad, -31, 18);
  r.m0 = q_angle(eph.m0_rad, -31, 32);
  r.e = q_unsigned(eph.e, -33, 32);
  r.cus = q_signed(eph.cus_rad, -31, 18);
  r.crc = q_signed(eph.crc_m, -6, 18);
  r.crs = q_signed(eph.crs_m, -6, 18);
  r.sqrta = q_unsigned(eph.sqrt_a_sqrtm, -19, 32);
  r.toe = q_time(bdt_tow(eph.toe), 3, 17);
  r.i0 = q_angle(eph.i0_rad, -31, 32);
  r.cic = q_signed(eph.cic_rad, -31, 18);
  r.omegadot = q_sc(eph.omega_dot_radps, -43, 24);
  r.cis = q_signed(eph.cis_rad, -31, 18);
  r.idot = q_sc(eph.idot_radps, -43, 14);
  r.omega0 = q_angle(eph.omega0_rad, -31, 32);
  r.omega = q_angle(eph.omega_rad, -31, 32);
  return r;
}

KlobucharCoefficients iono_from_raw(const Raw& r) {
  KlobucharCoefficients k;
  k.alpha = {d_signed(r.alpha0, 8, -30), d_signed(r.alpha1, 8, -27), d_signed(r.alpha2, 8, -24),
             d_signed(r.alpha3, 8, -24)};
  k.beta = {d_signed(r.beta0, 8, 11), d_signed(r.beta1, 8, 14), d_signed(r.beta2, 8, 16), d_signed(r.beta3, 8, 16)};
  return k;
}

// A BDT time of week near `sow_s` of BDT week `week`, the week resolved within half a week.
GpsTime resolve(int week, std::uint32_t sow_s, double t_s) {
  const double dt = t_s - static_cast<double>(sow_s);
  if (dt > 302400.0) --week;
  if (dt < -302400.0) ++week;
  return gps_from_bdt(week, t_s);
}

BeidouEphemeris eph_from_raw(const Raw& r, int prn, std::uint32_t sow_s) {
  BeidouEphemeris e;
  e.sat = SatId(GnssSystem::kBeidou, prn);
  const int week = static_cast<int>(r.wn);
  e.health = static_cast<int>(r.sath1);
  e.aodc = static_cast<int>(r.aodc);
  e.ura_m = bds_ura_m(static_cast<int>(r.urai));
  e.toc = resolve(week, sow_s, d_unsigned(r.toc, 3));
  e.tgd1_s = d_01ns(r.tgd1, 10);
  e.tgd2_s = d_01ns(r.tgd2, 10);
  e.af2_sps2 = d_signed(r.a2, 11, -66);
  e.af0_s = d_signed(r.a0, 24, -33);
  e.af1_sps = d_signed(r.a1, 22, -50);
  e.aode = static_cast<int>(r.aode);
  e.delta_n_radps = d_sc(r.dn, 16, -43);
  e.cuc_rad = d_signed(r.cuc, 18, -31);
  e.m0_rad = d_sc(r.m0, 32, -31);
  e.e = d_unsigned(r.e, -33);
  e.cus_rad = d_signed(r.cus, 18, -31);
  e.crc_m = d_signed(r.crc, 18, -6);
  e.crs_m = d_signed(r.crs, 18, -6);
  e.sqrt_a_sqrtm = d_unsigned(r.sqrta, -19);
  e.toe = resolve(week, sow_s, d_unsigned(r.toe, 3));
  e.i0_rad = d_sc(r.i0, 32, -31);
  e.cic_rad = d_signed(r.cic, 18, -31);
  e.omega_dot_radps = d_sc(r.omegadot, 24, -43);
  e.cis_rad = d_signed(r.cis, 18, -31);
  e.idot_radps = d_sc(r.idot, 14, -43);
  e.omega0_rad = d_sc(r.omega0, 32, -31);
  e.omega_rad = d_sc(r.omega, 32, -31);
  e.transmission_tow_s = static_cast<double>(sow_s);
  return e;
}

using R = Raw;
// D1 subframes 1-3 after the 38-bit header (5.2.3: subframe 1 ... subframe 3).
constexpr Slot kD1Sf1[] = {full(&R::sath1, 1),  full(&R::aodc, 5),   full(&R::urai, 4),
                           full(&R::wn, 13),    full(&R::toc, 17),   full(&R::tgd1, 10),
                           full(&R::tgd2, 10),  full(&R::alpha0, 8), full(&R::alpha1, 8),
                           full(&R::alpha2, 8), full(&R::alpha3, 8), full(&R::beta0, 8),
                           full(&R::beta1, 8),  full(&R::beta2, 8),  full(&R::beta3, 8),
                           full(&R::a2, 11),    full(&R::a0, 24),    full(&R::a1, 22),
                           full(&R::aode, 5)};
constexpr Slot kD1Sf2[] = {full(&R::dn, 16),  full(&R::cuc, 18), full(&R::m0, 32),
                           full(&R::e, 32),   full(&R::cus, 18), full(&R::crc, 18),
                           full(&R::crs, 18), full(&R::sqrta, 32), {&R::toe, 16, 15}};
constexpr Slot kD1Sf3[] = {{&R::toe, 14, 0},      full(&R::i0, 32),  full(&R::cic, 18),
                           full(&R::omegadot, 24), full(&R::cis, 18), full(&R::idot, 14),
                           full(&R::omega0, 32),   full(&R::omega, 32), reserved(1)};
// D2 subframe 1 pages 1-10 after the header and the 4-bit Pnum (5.3.2); the fields the ICD
// splits over two pages are sent MSBs first.
constexpr Slot kD2P1[] = {full(&R::sath1, 1), full(&R::aodc, 5),  full(&R::urai, 4),
                          full(&R::wn, 13),   full(&R::toc, 17),  full(&R::tgd1, 10),
                          full(&R::tgd2, 10)};
constexpr Slot kD2P2[] = {full(&R::alpha0, 8), full(&R::alpha1, 8), full(&R::alpha2, 8),
                          full(&R::alpha3, 8), full(&R::beta0, 8),  full(&R::beta1, 8),
                          full(&R::beta2, 8),  full(&R::beta3, 8)};
constexpr Slot kD2P3[] = {reserved(38), full(&R::a0, 24), {&R::a1, 21, 18}};
constexpr Slot kD2P4[] = {{&R::a1, 17, 0}, full(&R::a2, 11), full(&R::aode, 5), full(&R::dn, 16),
                          {&R::cuc, 17, 4}};
constexpr Slot kD2P5[] = {{&R::cuc, 3, 0}, full(&R::m0, 32), full(&R::cus, 18), {&R::e, 31, 22}};
constexpr Slot kD2P6[] = {{&R::e, 21, 0}, full(&R::sqrta, 32), {&R::cic, 17, 8}};
constexpr Slot kD2P7[] = {{&R::cic, 7, 0}, full(&R::cis, 18), full(&R::toe, 17), {&R::i0, 31, 11}};
constexpr Slot kD2P8[] = {{&R::i0, 10, 0}, full(&R::crc, 18), full(&R::crs, 18),
                          {&R::omegadot, 23, 5}};
constexpr Slot kD2P9[] = {{&R::omegadot, 4, 0}, full(&R::omega0, 32), {&R::omega, 31, 5}};
constexpr Slot kD2P10[] = {{&R::omega, 4, 0}, full(&R::idot, 14)};
constexpr std::span<const Slot> kD2Pages[] = {kD2P1, kD2P2, kD2P3, kD2P4, kD2P5,
                                              kD2P6, kD2P7, kD2P8, kD2P9, kD2P10};

void write_slots(BitWriter& w, const Raw& r, std::span<const Slot> slots) {
  for (const Slot& s : slots) {
    const int n = s.hi - s.lo + 1;
    if (s.field == nullptr) {
      w.zeros(n);
    } else {
      w.put((r.*s.field >> s.lo) & mask(n), n);
    }
  }
}
void read_slots(BitReader& rd, Raw& r, std::span<const Slot> slots) {
  for (const Slot& s : slots) {
    const int n = s.hi - s.lo + 1;
    if (s.field == nullptr) {
      rd.skip(n);
    } else {
      r.*s.field |= rd.get(n) << s.lo;
    }
  }
}

void put_header(BitWriter& w, int fra_id, std::uint32_t sow_s) {
  w.put(kPreamble, 11);
  w.zeros(4);  // Rev
  w.put(static_cast<std::uint32_t>(fra_id), 3);
  w.put(sow_s % kSecondsPerWeekU, 20);
}

// ---- D1 subframes 4 and 5 (5.2.3) ------------------------------------------------------------

void put_almanac(BitWriter& w, const BdsAlmanac& alm, int prn) {
  const BdsAlmanacEntry* a = nullptr;
  for (const BdsAlmanacEntry& e : alm.entries)
    if (e.prn == prn) a = &e;
  if (a == nullptr) {
    w.zeros(176);  // every parameter zero: no almanac for this satellite
  } else {
    w.put(q_unsigned(a->sqrt_a_sqrtm, -11, 24), 24);
    w.put(q_signed(a->af1_sps, -38, 11), 11);
    w.put(q_signed(a->af0_s, -20, 11), 11);
    w.put(q_angle(a->omega0_rad, -23, 24), 24);
    w.put(q_unsigned(a->e, -21, 17), 17);
    w.put(q_sc(a->delta_i_rad, -19, 16), 16);
    w.put(q_time(a->toa_s, 12, 8), 8);
    w.put(q_sc(a->omega_dot_radps, -38, 17), 17);
    w.put(q_angle(a->omega_rad, -23, 24), 24);
    w.put(q_angle(a->m0_rad, -23, 24), 24);
  }
  w.put(field_u(alm.am_ep_id, 2), 2);
}

void put_d1_page(BitWriter& w, int fra_id, int page, const BdsBroadcast& bc) {
  w.zeros(1);  // Rev
  w.put(static_cast<std::uint32_t>(page), 7);
  if (fra_id == 4) return put_almanac(w, bc.almanac, page);
  if (page <= 6) return put_almanac(w, bc.almanac, 24 + page);
  const auto hea = [&](int prn) { return field_u(bc.almanac.health[static_cast<std::size_t>(prn - 1)], 9); };
  if (page == 7) {
    for (int prn = 1; prn <= 19; ++prn) w.put(hea(prn), 9);
  } else if (page == 8) {
    for (int prn = 20; prn <= 30; ++prn) w.put(hea(prn), 9);
    w.put(low_bits(bc.almanac.wna, 8), 8);
    w.put(q_time(bc.almanac.toa_s, 12, 8), 8);
  } else if (page == 9) {
    const BdsGnssTimeOffsets& t = bc.time_offsets;
    w.zeros(30);
    w.put(quantise_lsb(t.a0_gps_s, 1e-10, 14, true), 14);
    w.put(quantise_lsb(t.a1_gps_sps, 1e-10, 16, true), 16);
    w.put(quantise_lsb(t.a0_gal_s, 1e-10, 14, true), 14);
    w.put(quantise_lsb(t.a1_gal_sps, 1e-10, 16, true), 16);
    w.put(quantise_lsb(t.a0_glo_s, 1e-10, 14, true), 14);
    w.put(quantise_lsb(t.a1_glo_sps, 1e-10, 16, true), 16);
  } else if (page == 10) {
    const BdsUtcParameters& u = bc.utc;
    w.put(quantise_lsb(u.dt_ls_s, 1.0, 8, true), 8);
    w.put(quantise_lsb(u.dt_lsf_s, 1.0, 8, true), 8);
    w.put(low_bits(u.wn_lsf, 8), 8);
    w.put(q_signed(u.a0_utc_s, -30, 32), 32);
    w.put(q_signed(u.a1_utc_sps, -50, 24), 24);
    w.put(field_u(u.dn, 8), 8);
  }
}

// Header fields of a subframe with a valid BCH, and a reader positioned after them.
std::optional<BdsHeader> header_of(const BdsSubframe& words, NavType type) {
  if (!bch_ok(words)) return std::nullopt;
  BitReader rd(words, 15);
  BdsHeader h;
  h.fra_id = static_cast<int>(rd.get(3));
  h.sow_s = rd.get(20);
  if (h.fra_id < 1 || h.fra_id > 5) return std::nullopt;
  if (type == NavType::kD1) {
    if (h.fra_id >= 4) {
      rd.skip(1);
      h.page = static_cast<int>(rd.get(7));
    }
  } else if (h.fra_id <= 4) {
    h.page = static_cast<int>(rd.get(4));
  } else {
    rd.skip(1);
    h.page = static_cast<int>(rd.get(7));
  }
  return h;
}

int clamp_int(int v, int lo, int hi) { return std::clamp(v, lo, hi); }

}  // namespace

NavType nav_type_for_prn(int prn) {
  return (prn >= 1 && prn <= 5) || (prn >= 59 && prn <= 63) ? NavType::kD2 : NavType::kD1;
}

BdtWeekSow bdt_from_gps(GpsTime t) {
  const WeekTow wt = to_week_tow(t.plus_s(-kGpsMinusBdt_s));
  const auto sow = static_cast<std::uint32_t>(std::floor(wt.tow_s));
  return {wt.week - kBdtWeek0InGpsWeeks, std::min(sow, kSecondsPerWeekU - 1)};
}

GpsTime gps_from_bdt(int bdt_week, double sow_s) {
  return from_week_tow(bdt_week + kBdtWeek0InGpsWeeks, sow_s).plus_s(kGpsMinusBdt_s);
}

BdsSubframe d1_subframe(int fra_id, int page, BdtWeekSow at, const BeidouEphemeris& eph,
                        const BdsBroadcast& bc) {
  fra_id = clamp_int(fra_id, 1, 5);
  BitWriter w;
  put_header(w, fra_id, at.sow_s);
  if (fra_id <= 3) {
    const Raw r = to_raw(eph, bc.iono, at.week);
    write_slots(w, r, fra_id == 1 ? std::span<const Slot>(kD1Sf1)
                                  : fra_id == 2 ? std::span<const Slot>(kD1Sf2)
                                                : std::span<const Slot>(kD1Sf3));
  } else {
    put_d1_page(w, fra_id, clamp_int(page, 1, 24), bc);
  }
  return w.finish();
}

BdsSubframe d2_subframe(int fra_id, int page, BdtWeekSow at, const BeidouEphemeris& eph,
                        const BdsBroadcast& bc) {
  fra_id = clamp_int(fra_id, 1, 5);
  BitWriter w;
  put_header(w, fra_id, at.sow_s);
  if (fra_id == 1) {
    page = clamp_int(page, 1, 10);
    w.put(static_cast<std::uint32_t>(page), 4);
    write_slots(w, to_raw(eph, bc.iono, at.week), kD2Pages[page - 1]);
  } else if (fra_id <= 4) {
    w.put(static_cast<std::uint32_t>(clamp_int(page, 1, 6)), 4);
  } else {
    w.zeros(1);
    w.put(static_cast<std::uint32_t>(clamp_int(page, 1, 120)), 7);
  }
  return w.finish();
}

BdsSlot d1_slot_at(double bdt_tow_s) {
  double t = std::isfinite(bdt_tow_s) ? std::fmod(bdt_tow_s, 604800.0) : 0.0;
  if (t < 0) t += 604800.0;
  const auto n = static_cast<std::uint32_t>(std::floor(t / 6.0));
  BdsSlot s;
  s.fra_id = static_cast<int>(n % 5) + 1;
  s.page = s.fra_id >= 4 ? static_cast<int>((n / 5) % 24) + 1 : 0;
  s.sow_s = n * 6;
  s.start_s = static_cast<double>(n) * 6.0;
  return s;
}

BdsSlot d2_slot_at(double bdt_tow_s) {
  double t = std::isfinite(bdt_tow_s) ? std::fmod(bdt_tow_s, 604800.0) : 0.0;
  if (t < 0) t += 604800.0;
  // In tenths of a second, so that 0.6 s steps are exact.
  const auto n = static_cast<std::uint32_t>(std::floor(t * 10.0 + 1e-6)) / 6;
  const std::uint32_t frame = n / 5;
  BdsSlot s;
  s.fra_id = static_cast<int>(n % 5) + 1;
  s.page = static_cast<int>(s.fra_id == 1 ? frame % 10 : s.fra_id <= 4 ? frame % 6 : frame % 120) + 1;
  s.sow_s = frame * 3;
  s.start_s = static_cast<double>(n * 6) / 10.0;
  return s;
}

std::optional<BdsSubframe> subframe_from_words(std::span<const std::uint32_t> words) {
  if (words.size() != 10) return std::nullopt;
  BdsSubframe s{};
  std::copy(words.begin(), words.end(), s.begin());
  return s;
}

bool bch_ok(const BdsSubframe& w) {
  for (const std::uint32_t word : w)
    if ((word >> 30) != 0) return false;
  if (((w[0] >> 19) & 0x7FFu) != kPreamble) return false;
  if (bch4(w[0] >> 4) != (w[0] & 0xFu)) return false;
  for (std::size_t k = 1; k < 10; ++k) {
    if (bch4(w[k] >> 19) != ((w[k] >> 4) & 0xFu)) return false;
    if (bch4(w[k] >> 8) != (w[k] & 0xFu)) return false;
  }
  return true;
}

std::uint32_t interleave_word(std::uint32_t u) {
  const std::uint32_t c1 = (((u >> 19) & 0x7FFu) << 4) | ((u >> 4) & 0xFu);
  const std::uint32_t c2 = (((u >> 8) & 0x7FFu) << 4) | (u & 0xFu);
  std::uint32_t air = 0;
  for (int i = 14; i >= 0; --i) air = (air << 2) | (((c1 >> i) & 1u) << 1) | ((c2 >> i) & 1u);
  return air;
}

std::uint32_t deinterleave_word(std::uint32_t air) {
  std::uint32_t c1 = 0;
  std::uint32_t c2 = 0;
  for (int i = 14; i >= 0; --i) {
    c1 = (c1 << 1) | ((air >> (2 * i + 1)) & 1u);
    c2 = (c2 << 1) | ((air >> (2 * i)) & 1u);
  }
  return ((c1 >> 4) << 19) | ((c2 >> 4) << 8) | ((c1 & 0xFu) << 4) | (c2 & 0xFu);
}

std::optional<BdsHeader> decode_header(const BdsSubframe& words, NavType type) {
  return header_of(words, type);
}

std::optional<BeidouEphemeris> decode_d1_ephemeris(const BdsSubframe& sf1, const BdsSubframe& sf2,
                                                   const BdsSubframe& sf3, int prn) {
  const std::array<const BdsSubframe*, 3> sfs = {&sf1, &sf2, &sf3};
  const std::array<std::span<const Slot>, 3> layouts = {kD1Sf1, kD1Sf2, kD1Sf3};
  Raw r{};
  std::uint32_t sow = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const auto h = header_of(*sfs[k], NavType::kD1);
    if (!h || h->fra_id != static_cast<int>(k) + 1) return std::nullopt;
    if (k == 0) sow = h->sow_s;
    BitReader rd(*sfs[k], kHeaderBits);
    read_slots(rd, r, layouts[k]);
  }
  return eph_from_raw(r, prn, sow);
}

std::optional<KlobucharCoefficients> decode_d1_iono(const BdsSubframe& sf1) {
  const auto h = header_of(sf1, NavType::kD1);
  if (!h || h->fra_id != 1) return std::nullopt;
  Raw r{};
  BitReader rd(sf1, kHeaderBits);
  read_slots(rd, r, kD1Sf1);
  return iono_from_raw(r);
}

std::optional<BeidouEphemeris> decode_d2_ephemeris(std::span<const BdsSubframe> pages, int prn) {
  if (pages.size() != 10) return std::nullopt;
  Raw r{};
  std::uint32_t sow = 0;
  for (std::size_t k = 0; k < 10; ++k) {
    const auto h = header_of(pages[k], NavType::kD2);
    if (!h || h->fra_id != 1 || h->page != static_cast<int>(k) + 1) return std::nullopt;
    if (k == 0) sow = h->sow_s;
    BitReader rd(pages[k], kHeaderBits + 4);
    read_slots(rd, r, kD2Pages[k]);
  }
  return eph_from_raw(r, prn, sow);
}

std::optional<KlobucharCoefficients> decode_d2_iono(const BdsSubframe& page2) {
  const auto h = header_of(page2, NavType::kD2);
  if (!h || h->fra_id != 1 || h->page != 2) return std::nullopt;
  Raw r{};
  BitReader rd(page2, kHeaderBits + 4);
  read_slots(rd, r, kD2P2);
  return iono_from_raw(r);
}

std::optional<BdsGnssTimeOffsets> decode_d1_time_offsets(const BdsSubframe& words) {
  const auto h = header_of(words, NavType::kD1);
  if (!h || h->fra_id != 5 || h->page != 9) return std::nullopt;
  BitReader rd(words, kHeaderBits + 8 + 30);
  BdsGnssTimeOffsets t;
  t.a0_gps_s = d_01ns(rd.get(14), 14);
  t.a1_gps_sps = d_01ns(rd.get(16), 16);
  t.a0_gal_s = d_01ns(rd.get(14), 14);
  t.a1_gal_sps = d_01ns(rd.get(16), 16);
  t.a0_glo_s = d_01ns(rd.get(14), 14);
  t.a1_glo_sps = d_01ns(rd.get(16), 16);
  return t;
}

std::optional<BdsUtcParameters> decode_d1_utc(const BdsSubframe& words) {
  const auto h = header_of(words, NavType::kD1);
  if (!h || h->fra_id != 5 || h->page != 10) return std::nullopt;
  BitReader rd(words, kHeaderBits + 8);
  BdsUtcParameters u;
  u.dt_ls_s = static_cast<int>(sign_extend(rd.get(8), 8));
  u.dt_lsf_s = static_cast<int>(sign_extend(rd.get(8), 8));
  u.wn_lsf = static_cast<int>(rd.get(8));
  u.a0_utc_s = d_signed(rd.get(32), 32, -30);
  u.a1_utc_sps = d_signed(rd.get(24), 24, -50);
  u.dn = static_cast<int>(rd.get(8));
  return u;
}

std::optional<BdsAlmanacPage> decode_d1_almanac(const BdsSubframe& words) {
  const auto h = header_of(words, NavType::kD1);
  if (!h || h->fra_id < 4 || h->page < 1 || h->page > (h->fra_id == 4 ? 24 : 6))
    return std::nullopt;
  BitReader rd(words, kHeaderBits + 8);
  BdsAlmanacPage p;
  BdsAlmanacEntry& a = p.entry;
  a.prn = h->fra_id == 4 ? h->page : 24 + h->page;
  a.sqrt_a_sqrtm = d_unsigned(rd.get(24), -11);
  a.af1_sps = d_signed(rd.get(11), 11, -38);
  a.af0_s = d_signed(rd.get(11), 11, -20);
  a.omega0_rad = d_sc(rd.get(24), 24, -23);
  a.e = d_unsigned(rd.get(17), -21);
  a.delta_i_rad = d_sc(rd.get(16), 16, -19);
  a.toa_s = d_unsigned(rd.get(8), 12);
  a.omega_dot_radps = d_sc(rd.get(17), 17, -38);
  a.omega_rad = d_sc(rd.get(24), 24, -23);
  a.m0_rad = d_sc(rd.get(24), 24, -23);
  p.am_ep_id = static_cast<int>(rd.get(2));
  return p;
}

std::optional<BdsAlmanac> decode_d1_health(const BdsSubframe& words, const BdsAlmanac& base) {
  const auto h = header_of(words, NavType::kD1);
  if (!h || h->fra_id != 5 || (h->page != 7 && h->page != 8)) return std::nullopt;
  BitReader rd(words, kHeaderBits + 8);
  BdsAlmanac a = base;
  const int first = h->page == 7 ? 1 : 20;
  const int last = h->page == 7 ? 19 : 30;
  for (int prn = first; prn <= last; ++prn)
    a.health[static_cast<std::size_t>(prn - 1)] = static_cast<int>(rd.get(9));
  if (h->page == 8) {
    a.wna = static_cast<int>(rd.get(8));
    a.toa_s = d_unsigned(rd.get(8), 12);
  }
  return a;
}

int bds_ura_index(double ura_m) {
  static constexpr std::array<double, 15> kUpper = {2.4,   3.4,   4.85,  6.85,   9.65,
                                                    13.65, 24.0,  48.0,  96.0,   192.0,
                                                    384.0, 768.0, 1536.0, 3072.0, 6144.0};
  if (std::isnan(ura_m)) return 15;
  for (std::size_t n = 0; n < kUpper.size(); ++n)
    if (ura_m <= kUpper[n]) return static_cast<int>(n);
  return 15;
}

double bds_ura_m(int ura_index) {
  const int n = clamp_int(ura_index, 0, 15);
  if (n <= 6) return std::pow(2.0, 1.0 + n / 2.0);
  if (n < 15) return std::ldexp(1.0, n - 2);
  return 8192.0;  // "unusable", beyond the table so that it maps back to 15
}

}  // namespace navemu::bdnav
