// Galileo I/NAV (E1-B) page encoder and decoders (Galileo OS SIS ICD issue 2.0/2.1, 4.3 and
// 5.1). See galileo_inav.hpp for the word format.
#include "protocols/galileo_inav.hpp"

#include <algorithm>
#include <cmath>

#include "core/time.hpp"
#include "protocols/nav_fields.hpp"

namespace navemu::inav {
namespace {

// ---- field quantisation (protocols/nav_fields.hpp) -----------------------------------------

using namespace navfield;
// Galileo's times of week come in units of 1 s, 60 s and 3600 s: q_time_units.

int resolve_week(std::uint64_t truncated, int modulus, int reference_week) {
  int diff = (static_cast<int>(truncated) - reference_week) % modulus;
  if (diff < 0) diff += modulus;
  if (diff >= modulus / 2) diff -= modulus;
  return reference_week + diff;
}

// ---- bit access on MSB-first byte and word buffers -----------------------------------------
// A value of more than 64 bits is written zero-extended (the almanac words' empty fields);
// get_bits keeps the last 64 of what it reads.

template <std::size_t N>
void set_bits(std::array<std::uint8_t, N>& buf, int pos, std::uint64_t v, int bits) {
  for (int i = bits - 1; i >= 0; --i, ++pos) {
    const auto byte = static_cast<std::size_t>(pos / 8);
    const auto bit = static_cast<std::uint8_t>(0x80u >> (pos % 8));
    if (i < 64 && ((v >> i) & 1u) != 0) {
      buf[byte] = static_cast<std::uint8_t>(buf[byte] | bit);
    } else {
      buf[byte] = static_cast<std::uint8_t>(buf[byte] & ~bit);
    }
  }
}
template <std::size_t N>
std::uint64_t get_bits(const std::array<std::uint8_t, N>& buf, int pos, int bits) {
  std::uint64_t v = 0;
  for (int i = 0; i < bits; ++i, ++pos)
    v = (v << 1) | ((static_cast<unsigned>(buf[static_cast<std::size_t>(pos / 8)]) >> (7 - pos % 8)) & 1u);
  return v;
}

class BitWriter {
 public:
  explicit BitWriter(InavWord& w) : w_(w) {}
  void put(std::uint64_t v, int bits) {
    set_bits(w_, pos_, v, bits);
    pos_ += bits;
  }
  int pos() const { return pos_; }

 private:
  InavWord& w_;
  int pos_ = 0;
};

class BitReader {
 public:
  explicit BitReader(const InavWord& w) : w_(w) {}
  std::uint64_t get(int bits) {
    const std::uint64_t v = get_bits(w_, pos_, bits);
    pos_ += bits;
    return v;
  }
  void skip(int bits) { pos_ += bits; }

 private:
  const InavWord& w_;
  int pos_ = 0;
};

// The spare/reserved bits inside a word: from the caller's extras, else the defaults.
class SpareBits {
 public:
  explicit SpareBits(const InavPageExtras& x) : given_(x.word_spare) {}
  void reserved(BitWriter& w, int bits) { put(w, bits, false); }
  void spare(BitWriter& w, int bits) { put(w, bits, true); }

 private:
  void put(BitWriter& w, int bits, bool alternate) {
    for (int i = 0; i < bits; ++i, ++used_) {
      std::uint64_t b = alternate ? static_cast<std::uint64_t>(i & 1) : 0u;
      if (given_ && used_ < 128) {
        const std::uint32_t word = (*given_)[static_cast<std::size_t>(used_ / 32)];
        b = (word >> (31 - used_ % 32)) & 1u;
      }
      w.put(b, 1);
    }
  }
  std::optional<std::array<std::uint32_t, 4>> given_;
  int used_ = 0;
};

// Positions (start, length) of the spare/reserved bits of each word type (ICD 4.3.5).
struct SpareField {
  int start;
  int bits;
};
constexpr std::array<SpareField, 2> spare_fields(int type) {
  switch (type) {
    case 0: return {{{8, 88}, {0, 0}}};
    case 1:
    case 2:
    case 4: return {{{126, 2}, {0, 0}}};
    case 5: return {{{105, 23}, {0, 0}}};
    case 6: return {{{125, 3}, {0, 0}}};
    case 7: return {{{122, 6}, {0, 0}}};
    case 8: return {{{127, 1}, {0, 0}}};
    case kWordDummy: return {{{6, 122}, {0, 0}}};
    default: return {{{0, 0}, {0, 0}}};
  }
}

// ---- words (ICD 4.3.5) ----------------------------------------------------------------------

double tow_of(GpsTime t) { return to_week_tow(t).tow_s; }

// Health nibbles from the RINEX 3.05 Galileo "SV health" bits.
std::uint64_t e1b_dvs(int h) { return static_cast<std::uint64_t>(h) & 1u; }
std::uint64_t e1b_hs(int h) { return (static_cast<std::uint64_t>(h) >> 1) & 3u; }
std::uint64_t e5b_dvs(int h) { return (static_cast<std::uint64_t>(h) >> 6) & 1u; }
std::uint64_t e5b_hs(int h) { return (static_cast<std::uint64_t>(h) >> 7) & 3u; }

void put_word0(BitWriter& w, SpareBits& s, int week, double tow, const InavPageExtras& x) {
  w.put(field_u(x.word0_time, 2), 2);  // Time field
  s.spare(w, 88);
  w.put(low_bits(week, 12), 12);  // WN
  w.put(q_time_units(tow, 1.0, 20), 20);  // TOW
}

void put_word1(BitWriter& w, SpareBits& s, const GalileoEphemeris& e) {
  w.put(low_bits(e.iod_nav, 10), 10);
  w.put(q_time_units(tow_of(e.toe), 60.0, 14), 14);  // toe, 60 s
  w.put(q_angle(e.m0_rad, -31, 32), 32);
  w.put(q_unsigned(e.e, -33, 32), 32);
  w.put(q_unsigned(e.sqrt_a_sqrtm, -19, 32), 32);
  s.reserved(w, 2);
}

void put_word2(BitWriter& w, SpareBits& s, const GalileoEphemeris& e) {
  w.put(low_bits(e.iod_nav, 10), 10);
  w.put(q_angle(e.omega0_rad, -31, 32), 32);
  w.put(q_angle(e.i0_rad, -31, 32), 32);
  w.put(q_angle(e.omega_rad, -31, 32), 32);
  w.put(q_sc(e.idot_radps, -43, 14), 14);
  s.reserved(w, 2);
}

void put_word3(BitWriter& w, const GalileoEphemeris& e) {
  w.put(low_bits(e.iod_nav, 10), 10);
  w.put(q_sc(e.omega_dot_radps, -43, 24), 24);
  w.put(q_sc(e.delta_n_radps, -43, 16), 16);
  w.put(q_signed(e.cuc_rad, -29, 16), 16);
  w.put(q_signed(e.cus_rad, -29, 16), 16);
  w.put(q_signed(e.crc_m, -5, 16), 16);
  w.put(q_signed(e.crs_m, -5, 16), 16);
  w.put(static_cast<std::uint64_t>(sisa_index(e.sisa_m)), 8);  // SISA(E1,E5b)
}

void put_word4(BitWriter& w, SpareBits& s, const GalileoEphemeris& e) {
  w.put(low_bits(e.iod_nav, 10), 10);
  w.put(field_u(e.sat.number(), 6), 6);  // SVID
  w.put(q_signed(e.cic_rad, -29, 16), 16);
  w.put(q_signed(e.cis_rad, -29, 16), 16);
  w.put(q_time_units(tow_of(e.toc), 60.0, 14), 14);  // toc, 60 s
  w.put(q_signed(e.af0_s, -34, 31), 31);
  w.put(q_signed(e.af1_sps, -46, 21), 21);
  w.put(q_signed(e.af2_sps2, -59, 6), 6);
  s.spare(w, 2);
}

void put_word5(BitWriter& w, SpareBits& s, const GalileoEphemeris& e, const InavSystemData& sys,
               int week, double tow) {
  w.put(q_unsigned(sys.ai0_sfu, -2, 11), 11);
  w.put(q_signed(sys.ai1_sfu_per_deg, -8, 11), 11);
  w.put(q_signed(sys.ai2_sfu_per_deg2, -15, 14), 14);
  for (const int f : sys.region_flags) w.put(field_u(f, 1), 1);
  w.put(q_signed(e.bgd_e1e5a_s, -32, 10), 10);
  w.put(q_signed(e.bgd_e1e5b_s, -32, 10), 10);
  w.put(e5b_hs(e.health), 2);
  w.put(e1b_hs(e.health), 2);
  w.put(e5b_dvs(e.health), 1);
  w.put(e1b_dvs(e.health), 1);
  w.put(low_bits(week, 12), 12);
  w.put(q_time_units(tow, 1.0, 20), 20);
  s.spare(w, 23);
}

void put_word6(BitWriter& w, SpareBits& s, const InavSystemData& sys, double tow) {
  w.put(q_signed(sys.a0_s, -30, 32), 32);
  w.put(q_signed(sys.a1_sps, -50, 24), 24);
  w.put(q_signed(sys.dt_ls_s, 0, 8), 8);
  w.put(q_time_units(sys.tot_s, 3600.0, 8), 8);
  w.put(low_bits(sys.wnot, 8), 8);
  w.put(low_bits(sys.wn_lsf, 8), 8);
  w.put(field_u(sys.dn, 3), 3);
  w.put(q_signed(sys.dt_lsf_s, 0, 8), 8);
  w.put(q_time_units(tow, 1.0, 20), 20);
  s.spare(w, 3);
}

// Words 7-9 "no almanac": IODa 0, WNa 0, t0a 0, SVIDs 0 (dummy satellite), parameters 0.
void put_almanac(BitWriter& w, SpareBits& s, int type) {
  w.put(0, 4);  // IODa
  if (type == 7) {
    w.put(0, 2 + 10 + 6 + 13 + 11 + 16 + 11 + 16 + 11 + 16);
    s.reserved(w, 6);
  } else if (type == 8) {
    w.put(0, 16 + 13 + 2 + 2 + 6 + 13 + 11 + 16 + 11 + 16 + 11);
    s.spare(w, 1);
  } else {
    w.put(0, 2 + 10 + 16 + 16 + 13 + 2 + 2 + 6 + 13 + 11 + 16 + 11);
  }
}

// Word 10: almanac of SVID3 (2/2), none here, and the GGTO (ICD 5.1.8).
void put_word10(BitWriter& w, const InavSystemData& sys) {
  w.put(0, 4 + 16 + 11 + 16 + 16 + 13 + 2 + 2);
  w.put(q_signed(sys.a0g_s, -35, 16), 16);
  w.put(q_signed(sys.a1g_sps, -51, 12), 12);
  w.put(q_time_units(sys.t0g_s, 3600.0, 8), 8);
  w.put(low_bits(sys.wn0g, 6), 6);
}

// ---- page pair (ICD 4.3.2) and CRC-24Q (ICD 5.1.9.4) -----------------------------------------

using PageBits = std::array<std::uint8_t, 32>;  // even part bits 0..127, odd part 128..255
constexpr int kOdd = 128;

std::uint32_t crc24q(const PageBits& p) {
  std::uint32_t crc = 0;
  auto feed = [&crc](std::uint64_t bit) {
    const std::uint32_t top = ((crc >> 23) & 1u) ^ static_cast<std::uint32_t>(bit);
    crc = (crc << 1) & 0xFFFFFFu;
    if (top != 0) crc ^= 0x864CFBu;  // 0x1864CFB without X^24
  };
  for (int i = 0; i < 114; ++i) feed(get_bits(p, i, 1));
  for (int i = 0; i < 82; ++i) feed(get_bits(p, kOdd + i, 1));
  return crc;
}

// SSP of the E1-B page starting at `tow` (ICD 2.0 4.3.2: SSP1, SSP2, SSP3 in turn from the
// page starting at GST 1 s modulo 6 s).
std::uint8_t ssp_for(double gst_tow_s) {
  constexpr std::array<std::uint8_t, 3> kSsp = {0x04, 0x2B, 0x2F};
  const double start = inav_page_start_s(gst_tow_s);
  const auto slot = static_cast<long long>(std::floor((start - 1.0) / 2.0));
  return kSsp[static_cast<std::size_t>(((slot % 3) + 3) % 3)];
}

double reduce_tow(double tow) {
  if (!std::isfinite(tow)) return 0.0;
  return tow - 604800.0 * std::floor(tow / 604800.0);
}

}  // namespace

// ---- public API ---------------------------------------------------------------------------

int sisa_index(double sisa_m_in) {
  if (!(sisa_m_in >= 0.0) || sisa_m_in > 6.0 + 1e-9) return 255;
  for (int i = 0; i <= 125; ++i)
    if (sisa_m(i) >= sisa_m_in - 1e-9) return i;
  return 255;
}

double sisa_m(int index) {
  if (index < 0 || index > 125) return -1.0;
  if (index < 50) return index * 0.01;
  if (index < 75) return 0.50 + (index - 50) * 0.02;
  if (index < 100) return 1.00 + (index - 75) * 0.04;
  return 2.00 + (index - 100) * 0.16;
}

InavWord inav_word(int word_type, int gst_week, double gst_tow_s, const GalileoEphemeris& eph,
                   const InavSystemData& sys, const InavPageExtras& extras) {
  if (word_type < 0 || (word_type > 10 && word_type != kWordDummy)) word_type = kWordDummy;
  InavWord word{};
  BitWriter w(word);
  SpareBits s(extras);
  w.put(static_cast<std::uint64_t>(word_type), 6);
  switch (word_type) {
    case 0: put_word0(w, s, gst_week, gst_tow_s, extras); break;
    case 1: put_word1(w, s, eph); break;
    case 2: put_word2(w, s, eph); break;
    case 3: put_word3(w, eph); break;
    case 4: put_word4(w, s, eph); break;
    case 5: put_word5(w, s, eph, sys, gst_week, gst_tow_s); break;
    case 6: put_word6(w, s, sys, gst_tow_s); break;
    case 7:
    case 8:
    case 9: put_almanac(w, s, word_type); break;
    case 10: put_word10(w, sys); break;
    default: s.spare(w, 122); break;  // dummy word
  }
  return word;
}

InavPage inav_page_from_word(const InavWord& word, double gst_tow_s,
                             const InavPageExtras& extras) {
  PageBits p{};
  // Even part: even/odd 0, page type 0 (nominal), data (1/2), tail zeros.
  set_bits(p, 2, get_bits(word, 0, 56), 56);
  set_bits(p, 58, get_bits(word, 56, 56), 56);
  // Odd part: even/odd 1, page type 0, data (2/2), Reserved 1, SAR, spare, CRC, SSP, tail.
  set_bits(p, kOdd, 1, 1);
  set_bits(p, kOdd + 2, get_bits(word, 112, 16), 16);
  set_bits(p, kOdd + 18, extras.reserved1 & mask(40), 40);
  set_bits(p, kOdd + 58, extras.sar & mask(22), 22);
  set_bits(p, kOdd + 80, extras.spare & 3u, 2);
  set_bits(p, kOdd + 82, crc24q(p), 24);
  set_bits(p, kOdd + 106, extras.ssp ? *extras.ssp : ssp_for(gst_tow_s), 8);
  InavPage out{};
  for (std::size_t k = 0; k < 8; ++k)
    out[k] = static_cast<std::uint32_t>(get_bits(p, static_cast<int>(32 * k), 32));
  out[8] = extras.word9;
  return out;
}

InavPage inav_page(int word_type, int gst_week, double gst_tow_s, const GalileoEphemeris& eph,
                   const InavSystemData& sys, const InavPageExtras& extras) {
  return inav_page_from_word(inav_word(word_type, gst_week, gst_tow_s, eph, sys, extras),
                             gst_tow_s, extras);
}

double inav_page_start_s(double gst_tow_s, InavSignal signal) {
  const double t = std::floor(reduce_tow(gst_tow_s));
  const double first = signal == InavSignal::kE1B ? 1.0 : 0.0;
  return first + 2.0 * std::floor((t - first) / 2.0);
}

int inav_word_type_for(double gst_tow_s, InavSignal signal) {
  // Slots of the E1-B and E5b-I columns of the nominal sub-frame (ICD 4.3.2), word types 16-22
  // as 0.
  constexpr std::array<int, 15> kE1b = {2, 4, 6, 7, 8, 0, 0, 0, 0, 0, 1, 3, 5, 0, 0};
  constexpr std::array<int, 15> kE5b = {1, 3, 5, 7, 8, 0, 0, 0, 0, 0, 2, 4, 6, 0, 0};
  const bool e1b = signal == InavSignal::kE1B;
  const auto start = static_cast<long long>(inav_page_start_s(gst_tow_s, signal));
  const long long s = start - (e1b ? 1 : 0);  // seconds since the sub-frame boundary (may be -2)
  const long long subframe = s >= 0 ? s / 30 : -1;
  const long long in_sub = ((s % 30) + 30) % 30;
  const int type = (e1b ? kE1b : kE5b)[static_cast<std::size_t>(in_sub / 2)];
  if ((type == 7 || type == 8) && (subframe & 1) != 0) return type + 2;
  return type;
}

bool inav_crc_ok(std::span<const std::uint32_t> words) {
  if (words.size() < 8) return false;
  PageBits p{};
  for (std::size_t k = 0; k < 8; ++k) set_bits(p, static_cast<int>(32 * k), words[k], 32);
  return crc24q(p) == get_bits(p, kOdd + 82, 24);
}

std::optional<InavDecodedPage> decode_inav_page(std::span<const std::uint32_t> words) {
  if (words.size() != 8 && words.size() != 9) return std::nullopt;
  if (!inav_crc_ok(words)) return std::nullopt;
  PageBits p{};
  for (std::size_t k = 0; k < 8; ++k) set_bits(p, static_cast<int>(32 * k), words[k], 32);
  if (get_bits(p, 0, 1) != 0 || get_bits(p, kOdd, 1) != 1) return std::nullopt;  // even, odd
  if (get_bits(p, 1, 1) != 0 || get_bits(p, kOdd + 1, 1) != 0) return std::nullopt;  // nominal
  InavDecodedPage d;
  set_bits(d.word, 0, get_bits(p, 2, 56), 56);
  set_bits(d.word, 56, get_bits(p, 58, 56), 56);
  set_bits(d.word, 112, get_bits(p, kOdd + 2, 16), 16);
  d.word_type = word_type_of(d.word);
  d.extras.reserved1 = get_bits(p, kOdd + 18, 40);
  d.extras.sar = static_cast<std::uint32_t>(get_bits(p, kOdd + 58, 22));
  d.extras.spare = static_cast<std::uint32_t>(get_bits(p, kOdd + 80, 2));
  d.extras.ssp = static_cast<std::uint8_t>(get_bits(p, kOdd + 106, 8));
  d.extras.word9 = words.size() == 9 ? words[8] : 0u;
  if (d.word_type == 0) d.extras.word0_time = static_cast<int>(get_bits(d.word, 6, 2));
  std::array<std::uint32_t, 4> spare{};
  std::array<std::uint8_t, 16> spare_bytes{};
  int n = 0;
  for (const SpareField f : spare_fields(d.word_type))  // up to 122 bits: bit by bit
    for (int i = 0; i < f.bits; ++i, ++n) set_bits(spare_bytes, n, get_bits(d.word, f.start + i, 1), 1);
  for (std::size_t k = 0; k < 4; ++k)
    spare[k] = static_cast<std::uint32_t>(get_bits(spare_bytes, static_cast<int>(32 * k), 32));
  d.extras.word_spare = spare;
  return d;
}

int word_type_of(const InavWord& word) { return static_cast<int>(get_bits(word, 0, 6)); }

bool decode_word_into(const InavWord& word, int gst_week, GalileoEphemeris& eph,
                      InavSystemData& sys, int* gst_week_out, double* gst_tow_out) {
  BitReader r(word);
  const int type = static_cast<int>(r.get(6));
  auto time_in_week = [gst_week](double tow) {
    return from_week_tow(gst_week + kGstWeek0InGpsWeeks, tow);
  };
  auto set_time = [&](std::uint64_t wn, std::uint64_t tow) {
    if (gst_week_out != nullptr) *gst_week_out = resolve_week(wn, 4096, gst_week);
    if (gst_tow_out != nullptr) *gst_tow_out = static_cast<double>(tow);
  };
  switch (type) {
    case 0: {
      r.skip(2 + 88);
      const std::uint64_t wn = r.get(12);
      set_time(wn, r.get(20));
      return true;
    }
    case 1:
      eph.iod_nav = static_cast<int>(r.get(10));
      eph.toe = time_in_week(static_cast<double>(r.get(14)) * 60.0);
      eph.m0_rad = d_sc(r.get(32), 32, -31);
      eph.e = d_unsigned(r.get(32), -33);
      eph.sqrt_a_sqrtm = d_unsigned(r.get(32), -19);
      return true;
    case 2:
      eph.iod_nav = static_cast<int>(r.get(10));
      eph.omega0_rad = d_sc(r.get(32), 32, -31);
      eph.i0_rad = d_sc(r.get(32), 32, -31);
      eph.omega_rad = d_sc(r.get(32), 32, -31);
      eph.idot_radps = d_sc(r.get(14), 14, -43);
      return true;
    case 3:
      eph.iod_nav = static_cast<int>(r.get(10));
      eph.omega_dot_radps = d_sc(r.get(24), 24, -43);
      eph.delta_n_radps = d_sc(r.get(16), 16, -43);
      eph.cuc_rad = d_signed(r.get(16), 16, -29);
      eph.cus_rad = d_signed(r.get(16), 16, -29);
      eph.crc_m = d_signed(r.get(16), 16, -5);
      eph.crs_m = d_signed(r.get(16), 16, -5);
      eph.sisa_m = sisa_m(static_cast<int>(r.get(8)));
      return true;
    case 4:
      eph.iod_nav = static_cast<int>(r.get(10));
      eph.sat = SatId(GnssSystem::kGalileo, static_cast<int>(r.get(6)));
      eph.cic_rad = d_signed(r.get(16), 16, -29);
      eph.cis_rad = d_signed(r.get(16), 16, -29);
      eph.toc = time_in_week(static_cast<double>(r.get(14)) * 60.0);
      eph.af0_s = d_signed(r.get(31), 31, -34);
      eph.af1_sps = d_signed(r.get(21), 21, -46);
      eph.af2_sps2 = d_signed(r.get(6), 6, -59);
      return true;
    case 5: {
      sys.ai0_sfu = d_unsigned(r.get(11), -2);
      sys.ai1_sfu_per_deg = d_signed(r.get(11), 11, -8);
      sys.ai2_sfu_per_deg2 = d_signed(r.get(14), 14, -15);
      for (int& f : sys.region_flags) f = static_cast<int>(r.get(1));
      eph.bgd_e1e5a_s = d_signed(r.get(10), 10, -32);
      eph.bgd_e1e5b_s = d_signed(r.get(10), 10, -32);
      const auto hs5b = static_cast<int>(r.get(2));
      const auto hs1b = static_cast<int>(r.get(2));
      const auto dvs5b = static_cast<int>(r.get(1));
      const auto dvs1b = static_cast<int>(r.get(1));
      eph.health = (eph.health & 0x38) | dvs1b | (hs1b << 1) | (dvs5b << 6) | (hs5b << 7);
      const std::uint64_t wn = r.get(12);
      set_time(wn, r.get(20));
      return true;
    }
    case 6:
      sys.a0_s = d_signed(r.get(32), 32, -30);
      sys.a1_sps = d_signed(r.get(24), 24, -50);
      sys.dt_ls_s = static_cast<int>(sign_extend(r.get(8), 8));
      sys.tot_s = static_cast<double>(r.get(8)) * 3600.0;
      sys.wnot = resolve_week(r.get(8), 256, gst_week);
      sys.wn_lsf = resolve_week(r.get(8), 256, gst_week);
      sys.dn = static_cast<int>(r.get(3));
      sys.dt_lsf_s = static_cast<int>(sign_extend(r.get(8), 8));
      if (gst_tow_out != nullptr) *gst_tow_out = static_cast<double>(r.get(20));
      return true;
    case 10:
      r.skip(4 + 16 + 11 + 16 + 16 + 13 + 2 + 2);
      sys.a0g_s = d_signed(r.get(16), 16, -35);
      sys.a1g_sps = d_signed(r.get(12), 12, -51);
      sys.t0g_s = static_cast<double>(r.get(8)) * 3600.0;
      sys.wn0g = resolve_week(r.get(6), 64, gst_week);
      return true;
    default: return false;
  }
}

std::optional<GalileoEphemeris> decode_ephemeris(const InavWord& w1, const InavWord& w2,
                                                 const InavWord& w3, const InavWord& w4,
                                                 const InavWord& w5, int reference_gst_week) {
  const std::array<const InavWord*, 5> words = {&w1, &w2, &w3, &w4, &w5};
  for (std::size_t i = 0; i < 5; ++i)
    if (word_type_of(*words[i]) != static_cast<int>(i) + 1) return std::nullopt;
  const std::uint64_t iod = get_bits(w1, 6, 10);
  for (std::size_t i = 1; i < 4; ++i)
    if (get_bits(*words[i], 6, 10) != iod) return std::nullopt;
  GalileoEphemeris eph;
  InavSystemData sys;
  int week = reference_gst_week;
  double tow = 0.0;
  decode_word_into(w5, reference_gst_week, eph, sys, &week, &tow);
  for (std::size_t i = 0; i < 4; ++i) decode_word_into(*words[i], week, eph, sys);
  // toe and toc in the week that puts them nearest the transmission time.
  const GpsTime now = from_week_tow(week + kGstWeek0InGpsWeeks, tow);
  auto nearest = [now](GpsTime t) {
    const double dt = seconds_between(t, now);
    if (dt > 302400.0) return t.plus_s(-604800.0);
    if (dt < -302400.0) return t.plus_s(604800.0);
    return t;
  };
  eph.toe = nearest(eph.toe);
  eph.toc = nearest(eph.toc);
  eph.data_sources = (1 << 0) | (1 << 9);  // I/NAV E1-B; af0-af2, toc for E5b/E1
  eph.transmission_tow_s = tow;
  return eph;
}

std::optional<InavSystemData> decode_system_data(const InavWord& w5, const InavWord& w6,
                                                 const InavWord& w10, int reference_gst_week) {
  if (word_type_of(w5) != 5 || word_type_of(w6) != 6 || word_type_of(w10) != 10)
    return std::nullopt;
  InavSystemData sys;
  GalileoEphemeris eph;
  for (const InavWord* w : {&w5, &w6, &w10}) decode_word_into(*w, reference_gst_week, eph, sys);
  return sys;
}

}  // namespace navemu::inav
