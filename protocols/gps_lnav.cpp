// GPS LNAV subframe encoder and decoders (IS-GPS-200 Appendix II, 20.3). See gps_lnav.hpp for
// the word format.
#include "protocols/gps_lnav.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>

#include "protocols/nav_fields.hpp"

namespace navemu::lnav {
namespace {

// ---- parity (20.3.5.2, Table 20-XIV) ------------------------------------------------------

// Mask over the 24 source data bits d1..d24 held right-aligned (d1 = bit 23).
constexpr std::uint32_t data_mask(std::initializer_list<int> bits) {
  std::uint32_t m = 0;
  for (const int b : bits) m |= 1u << (24 - b);
  return m;
}

// D25..D30: the data bits each parity bit sums, and which of D29*/D30* it adds.
constexpr std::array<std::uint32_t, 6> kParityMask = {
    data_mask({1, 2, 3, 5, 6, 10, 11, 12, 13, 14, 17, 18, 20, 23}),     // D25, + D29*
    data_mask({2, 3, 4, 6, 7, 11, 12, 13, 14, 15, 18, 19, 21, 24}),     // D26, + D30*
    data_mask({1, 3, 4, 5, 7, 8, 12, 13, 14, 15, 16, 19, 20, 22}),      // D27, + D29*
    data_mask({2, 4, 5, 6, 8, 9, 13, 14, 15, 16, 17, 20, 21, 23}),      // D28, + D30*
    data_mask({1, 3, 5, 6, 7, 9, 10, 14, 15, 16, 17, 18, 21, 22, 24}),  // D29, + D30*
    data_mask({3, 5, 6, 8, 9, 10, 11, 13, 15, 19, 22, 23, 24}),         // D30, + D29*
};
constexpr std::array<bool, 6> kAddsD30 = {false, true, false, true, true, false};

constexpr std::uint32_t kData24 = 0xFFFFFF;

std::uint32_t odd(std::uint32_t v) { return static_cast<std::uint32_t>(std::popcount(v)) & 1u; }

// D25..D30 (D25 = bit 5) of source data d1..d24 after a word ending in D29*, D30*.
std::uint32_t parity6(std::uint32_t d, std::uint32_t d29s, std::uint32_t d30s) {
  std::uint32_t p = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    const std::uint32_t bit = odd(d & kParityMask[i]) ^ (kAddsD30[i] ? d30s : d29s);
    p = (p << 1) | bit;
  }
  return p;
}

// Bits 23 and 24 of words 2 and 10 such that D29 = D30 = 0 as transmitted (20.3.5.2): D29
// depends on d24 but not d23, D30 on both, so d24 is fixed first.
std::uint32_t solve_t_bits(std::uint32_t d, std::uint32_t d29s, std::uint32_t d30s) {
  d &= kData24 & ~3u;
  if ((odd(d & kParityMask[4]) ^ d30s) != 0) d |= 1u;
  if ((odd(d & kParityMask[5]) ^ d29s) != 0) d |= 2u;
  return d;
}

// Source data of ten words (24 bits each, t bits of words 2 and 10 still zero) to the words
// in the u-blox form: parity over the upright data with the transmitted D29*, D30*, then the
// word complemented with its two leading bits where the transmitted D30* is 1, which leaves
// bits 29..6 upright, bit 30 zero, bit 31 = D29* xor D30*.
LnavSubframe finish(std::array<std::uint32_t, 10> data) {
  LnavSubframe out{};
  std::uint32_t d29s = 0;  // the previous subframe's word 10 ends with D29 = D30 = 0
  std::uint32_t d30s = 0;
  for (std::size_t k = 0; k < 10; ++k) {
    std::uint32_t d = data[k] & kData24;
    if (k == 1 || k == 9) d = solve_t_bits(d, d29s, d30s);
    const std::uint32_t p = parity6(d, d29s, d30s);
    out[k] = ((d29s ^ d30s) << 31) | (d << 6) | (d30s != 0 ? (p ^ 0x3Fu) : p);
    d29s = (p >> 1) & 1u;
    d30s = p & 1u;
  }
  return out;
}

// ---- field quantisation (protocols/nav_fields.hpp) -----------------------------------------

using namespace navfield;

// ---- the data bits of a subframe as one bit stream ----------------------------------------

// Words 3..10 of every subframe are one stream of 190 data bits (8 x 24 minus the two t bits
// of word 10); fields run on across word boundaries (Figure 20-1), so a field split over two
// words (M0, e, sqrt A, IODC, A0, ...) needs no special case.
constexpr int kBodyStart = 48;  // bit 1 of word 3, counting the 24 data bits of each word
constexpr int kBodyEnd = 238;   // bit 23 of word 10 (the t bits)

class BitWriter {
 public:
  explicit BitWriter(std::array<std::uint32_t, 10>& data) : data_(data) {}
  void put(std::uint64_t v, int bits) {
    for (int i = bits - 1; i >= 0; --i) {
      const auto bit = static_cast<std::uint32_t>((v >> i) & 1u);
      const auto word = static_cast<std::size_t>(pos_ / 24);
      data_[word] |= bit << (23 - pos_ % 24);
      ++pos_;
    }
  }
  // Alternating ones and zeros, beginning with one, to the end of the stream.
  void alternate() {
    for (std::uint32_t b = 1; pos_ < kBodyEnd; b ^= 1u) put(b, 1);
  }
  void zeros(int bits) { pos_ += bits; }
  int pos() const { return pos_; }

 private:
  std::array<std::uint32_t, 10>& data_;
  int pos_ = kBodyStart;
};

class BitReader {
 public:
  explicit BitReader(const LnavSubframe& words) {
    for (std::size_t k = 0; k < 10; ++k) {
      std::uint32_t w = words[k];
      if ((w & 0x40000000u) != 0) w = ~w;  // transmitted form: complemented data
      data_[k] = (w >> 6) & kData24;
    }
  }
  std::uint32_t get(int bits) {
    std::uint32_t v = 0;
    for (int i = 0; i < bits; ++i) {
      const auto word = static_cast<std::size_t>(pos_ / 24);
      v = (v << 1) | ((data_[word] >> (23 - pos_ % 24)) & 1u);
      ++pos_;
    }
    return v;
  }
  void skip(int bits) { pos_ += bits; }
  std::uint32_t word(std::size_t k) const { return data_[k]; }

 private:
  std::array<std::uint32_t, 10> data_{};
  int pos_ = kBodyStart;
};

// ---- TLM and HOW (20.3.3.1, 20.3.3.2) -----------------------------------------------------

void put_tlm_how(std::array<std::uint32_t, 10>& data, const LnavEphemeris& eph,
                 std::uint32_t tow_count_next, int subframe_id) {
  data[0] = static_cast<std::uint32_t>((kPreamble << 16) | (field_u(eph.tlm_message, 14) << 2) |
                                       (field_u(eph.integrity_status_flag, 1) << 1));  // bit 24 reserved
  data[1] = static_cast<std::uint32_t>(((tow_count_next % kTowCountsPerWeek) << 7) |
                                       (field_u(eph.alert_flag, 1) << 6) | (field_u(eph.anti_spoof_flag, 1) << 5) |
                                       (field_u(subframe_id, 3) << 2));  // bits 23, 24: t, solved in finish()
}

// ---- subframes 1-3 (Figure 20-1 sheets 1-3; Tables 20-I, 20-III) -------------------------

void put_subframe1(BitWriter& w, const LnavEphemeris& eph) {
  const std::uint64_t iodc = low_bits(eph.iodc, 10);
  w.put(low_bits(eph.week, 10), 10);  // WN
  w.put(field_u(eph.codes_on_l2, 2), 2);
  w.put(field_u(eph.ura_index, 4), 4);
  w.put(field_u(eph.health, 6), 6);
  w.put(iodc >> 8, 2);  // IODC, 2 MSBs (word 3)
  w.put(field_u(eph.l2p_data_flag, 1), 1);
  w.zeros(23 + 24 + 24 + 16);  // reserved: rest of word 4, words 5 and 6, 16 MSBs of word 7
  w.put(q_signed(eph.tgd_s, -31, 8), 8);
  w.put(iodc & 0xFFu, 8);  // IODC, 8 LSBs (word 8)
  w.put(q_time(eph.toc_s, 4, 16), 16);
  w.put(q_signed(eph.af2_sps2, -55, 8), 8);
  w.put(q_signed(eph.af1_sps, -43, 16), 16);
  w.put(q_signed(eph.af0_s, -31, 22), 22);
}

void put_subframe2(BitWriter& w, const LnavEphemeris& eph) {
  w.put(low_bits(eph.iode, 8), 8);
  w.put(q_signed(eph.crs_m, -5, 16), 16);
  w.put(q_sc(eph.delta_n_radps, -43, 16), 16);
  w.put(q_angle(eph.m0_rad, -31, 32), 32);
  w.put(q_signed(eph.cuc_rad, -29, 16), 16);
  w.put(q_unsigned(eph.e, -33, 32), 32);
  w.put(q_signed(eph.cus_rad, -29, 16), 16);
  w.put(q_unsigned(eph.sqrt_a_sqrtm, -19, 32), 32);
  w.put(q_time(eph.toe_s, 4, 16), 16);
  w.put(field_u(eph.fit_interval_flag, 1), 1);
  w.put(field_u(eph.aodo, 5), 5);
}

void put_subframe3(BitWriter& w, const LnavEphemeris& eph) {
  w.put(q_signed(eph.cic_rad, -29, 16), 16);
  w.put(q_angle(eph.omega0_rad, -31, 32), 32);
  w.put(q_signed(eph.cis_rad, -29, 16), 16);
  w.put(q_angle(eph.i0_rad, -31, 32), 32);
  w.put(q_signed(eph.crc_m, -5, 16), 16);
  w.put(q_angle(eph.omega_rad, -31, 32), 32);
  w.put(q_sc(eph.omega_dot_radps, -43, 24), 24);
  w.put(low_bits(eph.iode, 8), 8);
  w.put(q_sc(eph.idot_radps, -43, 14), 14);
}

// ---- subframes 4 and 5 (Figure 20-1 sheets 4-11, Table 20-V) ------------------------------

constexpr std::uint32_t kDataId = 1;  // binary 01, the LNAV structure (20.3.3.5.1.1)

// SV ID (page ID) of each page of subframe 4 (Table 20-V); subframe 5 pages 1-24 carry the
// SV's own ID, page 25 ID 51.
constexpr std::array<int, 26> kSf4SvId = {0,  57, 25, 26, 27, 28, 57, 29, 30, 31, 32, 57, 62,
                                          52, 53, 54, 57, 55, 56, 58, 59, 57, 60, 61, 62, 63};
constexpr int kSf4IonoUtc = 56;
constexpr int kSf4SpecialMessage = 55;
constexpr int kSf4Nmct = 52;
constexpr int kSf4Config = 63;
constexpr int kSf5Health = 51;

const LnavAlmanacEntry* find_entry(const LnavAlmanac& alm, int sv_id) {
  for (const auto& e : alm.entries)
    if (e.sv_id == sv_id) return &e;
  return nullptr;
}

// Six-bit health of the page 25 summaries (20.3.3.5.1.3): NAV data summary bit + the five
// signal health bits; 111111 for an SV without almanac.
std::uint32_t six_bit_health(const LnavAlmanacEntry* e) {
  if (e == nullptr) return 0x3F;
  const std::uint64_t h = field_u(e->health, 8);
  return ((h >> 5) != 0 ? 0x20u : 0u) | static_cast<std::uint32_t>(h & 0x1Fu);
}

void put_almanac(BitWriter& w, const LnavAlmanacEntry& a) {
  w.put(kDataId, 2);
  w.put(field_u(a.sv_id, 6), 6);
  w.put(q_unsigned(a.e, -21, 16), 16);
  w.put(q_time(a.toa_s, 12, 8), 8);
  w.put(q_sc(a.delta_i_rad, -19, 16), 16);
  w.put(q_sc(a.omega_dot_radps, -38, 16), 16);
  w.put(field_u(a.health, 8), 8);
  w.put(q_unsigned(a.sqrt_a_sqrtm, -11, 24), 24);
  w.put(q_angle(a.omega0_rad, -23, 24), 24);
  w.put(q_angle(a.omega_rad, -23, 24), 24);
  w.put(q_angle(a.m0_rad, -23, 24), 24);
  const std::uint64_t af0 = q_signed(a.af0_s, -20, 11);
  w.put(af0 >> 3, 8);  // af0, 8 MSBs
  w.put(q_signed(a.af1_sps, -38, 11), 11);
  w.put(af0 & 7u, 3);  // af0, 3 LSBs
}

void put_dummy(BitWriter& w, int sv_id) {
  w.put(kDataId, 2);
  w.put(field_u(sv_id, 6), 6);
  w.alternate();
}

void put_iono_utc(BitWriter& w, const LnavIonoUtc& p) {
  w.put(kDataId, 2);
  w.put(kSf4IonoUtc, 6);
  constexpr std::array<int, 4> kAlphaExp = {-30, -27, -24, -24};
  constexpr std::array<int, 4> kBetaExp = {11, 14, 16, 16};
  for (std::size_t i = 0; i < 4; ++i) w.put(q_signed(p.alpha[i], kAlphaExp[i], 8), 8);
  for (std::size_t i = 0; i < 4; ++i) w.put(q_signed(p.beta[i], kBetaExp[i], 8), 8);
  w.put(q_signed(p.a1_sps, -50, 24), 24);
  w.put(q_signed(p.a0_s, -30, 32), 32);
  w.put(q_time(p.tot_s, 12, 8), 8);
  w.put(low_bits(p.wnt, 8), 8);
  w.put(q_signed(p.dt_ls_s, 0, 8), 8);
  w.put(low_bits(p.wn_lsf, 8), 8);
  w.put(field_u(p.dn, 8), 8);
  w.put(q_signed(p.dt_lsf_s, 0, 8), 8);
  // 14 reserved bits to the t bits.
}

void put_special_message(BitWriter& w, std::string_view msg) {
  w.put(kDataId, 2);
  w.put(kSf4SpecialMessage, 6);
  for (std::size_t i = 0; i < 22; ++i)
    w.put(i < msg.size() ? static_cast<std::uint8_t>(msg[i]) : std::uint32_t{' '}, 8);
  // 6 reserved bits (zero, as the ZED-F9P capture shows).
}

// Page 13: availability indicator 00 and every estimated range deviation 100000, "no valid
// ERD" (20.3.3.5.1.9).
void put_nmct(BitWriter& w) {
  w.put(kDataId, 2);
  w.put(kSf4Nmct, 6);
  w.put(0, 2);
  for (int i = 0; i < 30; ++i) w.put(0x20, 6);
}

// Subframe 4 page 25: A-S flag and configuration of SVs 1-32, health of SVs 25-32
// (20.3.3.5.1.3-4).
void put_sf4_config(BitWriter& w, const LnavAlmanac& alm) {
  w.put(kDataId, 2);
  w.put(kSf4Config, 6);
  for (int sv_id = 1; sv_id <= 32; ++sv_id) {
    const LnavAlmanacEntry* e = find_entry(alm, sv_id);
    const std::uint64_t v =
        e == nullptr ? 0u : (field_u(e->anti_spoof_flag, 1) << 3) | field_u(e->sv_config, 3);
    w.put(v, 4);
  }
  w.zeros(2);
  for (int sv_id = 25; sv_id <= 32; ++sv_id) w.put(six_bit_health(find_entry(alm, sv_id)), 6);
  // 4 reserved bits to the t bits.
}

// Subframe 5 page 25: toa, WNa and the health of SVs 1-24 (20.3.3.5.1.3, 20.3.3.5.1.5).
void put_sf5_health(BitWriter& w, const LnavAlmanac& alm) {
  w.put(kDataId, 2);
  w.put(kSf5Health, 6);
  w.put(q_time(alm.toa_s, 12, 8), 8);
  w.put(low_bits(alm.week, 8), 8);
  for (int sv_id = 1; sv_id <= 24; ++sv_id) w.put(six_bit_health(find_entry(alm, sv_id)), 6);
  // 6 reserved bits and 16 bits reserved for system use, to the t bits.
}

void put_page(BitWriter& w, int subframe_id, int page, const LnavIonoUtc& iono_utc,
              const LnavAlmanac& alm) {
  const int sv_id = subframe_id == 5 ? (page == 25 ? kSf5Health : page)
                                     : kSf4SvId[static_cast<std::size_t>(page)];
  if (sv_id >= 1 && sv_id <= 32) {
    const LnavAlmanacEntry* e = find_entry(alm, sv_id);
    if (e != nullptr) {
      put_almanac(w, *e);
    } else {
      put_dummy(w, 0);  // dummy SV (20.3.3.5.1.1)
    }
    return;
  }
  switch (sv_id) {
    case kSf4IonoUtc: put_iono_utc(w, iono_utc); break;
    case kSf4SpecialMessage: put_special_message(w, alm.special_message); break;
    case kSf4Nmct: put_nmct(w); break;
    case kSf4Config: put_sf4_config(w, alm); break;
    case kSf5Health: put_sf5_health(w, alm); break;
    default: put_dummy(w, sv_id); break;  // reserved pages
  }
}

int resolve_week(std::uint32_t truncated, int modulus, int reference_week) {
  int diff = (static_cast<int>(truncated) - reference_week) % modulus;
  if (diff < 0) diff += modulus;
  if (diff >= modulus / 2) diff -= modulus;
  return reference_week + diff;
}

bool is_subframe(const LnavSubframe& words, int id) {
  return lnav_parity_ok(words) && decode_tlm_how(words).subframe_id == id;
}

}  // namespace

// ---- public API ---------------------------------------------------------------------------

LnavSubframe lnav_subframe(int subframe_id, std::uint32_t tow_count_next, const LnavEphemeris& eph,
                           const LnavIonoUtc& iono_utc, int page, const LnavAlmanac& almanac) {
  subframe_id = std::clamp(subframe_id, 1, 5);
  page = std::clamp(page, 1, 25);
  std::array<std::uint32_t, 10> data{};
  put_tlm_how(data, eph, tow_count_next, subframe_id);
  BitWriter w(data);
  switch (subframe_id) {
    case 1: put_subframe1(w, eph); break;
    case 2: put_subframe2(w, eph); break;
    case 3: put_subframe3(w, eph); break;
    default: put_page(w, subframe_id, page, iono_utc, almanac); break;
  }
  return finish(data);
}

int lnav_subframe_id_for(std::uint32_t tow_count_next) {
  const std::uint32_t start =
      (tow_count_next % kTowCountsPerWeek + kTowCountsPerWeek - 1) % kTowCountsPerWeek;
  return static_cast<int>(start % 5) + 1;
}

int lnav_page_for(std::uint32_t tow_count_next) {
  const std::uint32_t start =
      (tow_count_next % kTowCountsPerWeek + kTowCountsPerWeek - 1) % kTowCountsPerWeek;
  return static_cast<int>((start / 5) % 25) + 1;
}

bool lnav_parity_ok(const LnavSubframe& words) {
  for (std::size_t k = 0; k < 10; ++k) {
    const std::uint32_t w = words[k];
    const std::uint32_t d29s = (w >> 31) & 1u;
    const std::uint32_t d30s = (w >> 30) & 1u;
    std::uint32_t d = (w >> 6) & kData24;
    if (d30s != 0) d ^= kData24;
    if (parity6(d, d29s, d30s) != (w & 0x3Fu)) return false;
    if (k == 0) {
      if ((d >> 16) != kPreamble) return false;
    } else {
      const std::uint32_t prev = words[k - 1];
      if ((d29s ^ d30s) != (((prev >> 1) ^ prev) & 1u)) return false;
    }
    if ((k == 1 || k == 9) && (((w >> 1) ^ w) & 1u) != 0) return false;
  }
  return true;
}

LnavSubframe lnav_as_transmitted(const LnavSubframe& words) {
  LnavSubframe out{};
  std::uint32_t d29s = 0;
  std::uint32_t d30s = 0;
  for (std::size_t k = 0; k < 10; ++k) {
    // To the u-blox form first (a transmitted word with D30* = 1 complemented as a whole).
    std::uint32_t w = (words[k] & 0x40000000u) != 0 ? ~words[k] : words[k];
    if (k == 0) {
      d29s = (w >> 31) & 1u;
      d30s = 0;
    }
    if (d30s != 0) w = ~w;
    w = (w & 0x3FFFFFFFu) | (d29s << 31) | (d30s << 30);
    out[k] = w;
    d29s = (w >> 1) & 1u;
    d30s = w & 1u;
  }
  return out;
}

LnavTlmHow decode_tlm_how(const LnavSubframe& words) {
  const BitReader r(words);
  const std::uint32_t tlm = r.word(0);
  const std::uint32_t how = r.word(1);
  LnavTlmHow h;
  h.tlm_message = static_cast<int>((tlm >> 2) & 0x3FFFu);
  h.integrity_status_flag = static_cast<int>((tlm >> 1) & 1u);
  h.tow_count = how >> 7;
  h.alert_flag = static_cast<int>((how >> 6) & 1u);
  h.anti_spoof_flag = static_cast<int>((how >> 5) & 1u);
  h.subframe_id = static_cast<int>((how >> 2) & 7u);
  return h;
}

std::optional<LnavEphemeris> decode_ephemeris(const LnavSubframe& sf1, const LnavSubframe& sf2,
                                              const LnavSubframe& sf3, int reference_week) {
  if (!is_subframe(sf1, 1) || !is_subframe(sf2, 2) || !is_subframe(sf3, 3)) return std::nullopt;
  LnavEphemeris eph;
  const LnavTlmHow h = decode_tlm_how(sf1);
  eph.tlm_message = h.tlm_message;
  eph.integrity_status_flag = h.integrity_status_flag;
  eph.alert_flag = h.alert_flag;
  eph.anti_spoof_flag = h.anti_spoof_flag;

  BitReader r1(sf1);
  eph.week = resolve_week(r1.get(10), 1024, reference_week);
  eph.codes_on_l2 = static_cast<int>(r1.get(2));
  eph.ura_index = static_cast<int>(r1.get(4));
  eph.health = static_cast<int>(r1.get(6));
  const std::uint32_t iodc_msb = r1.get(2);
  eph.l2p_data_flag = static_cast<int>(r1.get(1));
  r1.skip(23 + 24 + 24 + 16);
  eph.tgd_s = d_signed(r1.get(8), 8, -31);
  eph.iodc = static_cast<int>((iodc_msb << 8) | r1.get(8));
  eph.toc_s = d_unsigned(r1.get(16), 4);
  eph.af2_sps2 = d_signed(r1.get(8), 8, -55);
  eph.af1_sps = d_signed(r1.get(16), 16, -43);
  eph.af0_s = d_signed(r1.get(22), 22, -31);

  BitReader r2(sf2);
  const auto iode2 = static_cast<int>(r2.get(8));
  eph.crs_m = d_signed(r2.get(16), 16, -5);
  eph.delta_n_radps = d_sc(r2.get(16), 16, -43);
  eph.m0_rad = d_sc(r2.get(32), 32, -31);
  eph.cuc_rad = d_signed(r2.get(16), 16, -29);
  eph.e = d_unsigned(r2.get(32), -33);
  eph.cus_rad = d_signed(r2.get(16), 16, -29);
  eph.sqrt_a_sqrtm = d_unsigned(r2.get(32), -19);
  eph.toe_s = d_unsigned(r2.get(16), 4);
  eph.fit_interval_flag = static_cast<int>(r2.get(1));
  eph.aodo = static_cast<int>(r2.get(5));

  BitReader r3(sf3);
  eph.cic_rad = d_signed(r3.get(16), 16, -29);
  eph.omega0_rad = d_sc(r3.get(32), 32, -31);
  eph.cis_rad = d_signed(r3.get(16), 16, -29);
  eph.i0_rad = d_sc(r3.get(32), 32, -31);
  eph.crc_m = d_signed(r3.get(16), 16, -5);
  eph.omega_rad = d_sc(r3.get(32), 32, -31);
  eph.omega_dot_radps = d_sc(r3.get(24), 24, -43);
  const auto iode3 = static_cast<int>(r3.get(8));
  eph.idot_radps = d_sc(r3.get(14), 14, -43);

  if (iode2 != iode3 || iode2 != (eph.iodc & 0xFF)) return std::nullopt;
  eph.iode = iode2;
  return eph;
}

LnavPageId decode_page_id(const LnavSubframe& words) {
  BitReader r(words);
  LnavPageId id;
  id.data_id = static_cast<int>(r.get(2));
  id.sv_id = static_cast<int>(r.get(6));
  return id;
}

std::optional<LnavIonoUtc> decode_iono_utc(const LnavSubframe& words, int reference_week) {
  if (!is_subframe(words, 4) || decode_page_id(words).sv_id != kSf4IonoUtc) return std::nullopt;
  BitReader r(words);
  r.skip(8);
  LnavIonoUtc p;
  constexpr std::array<int, 4> kAlphaExp = {-30, -27, -24, -24};
  constexpr std::array<int, 4> kBetaExp = {11, 14, 16, 16};
  for (std::size_t i = 0; i < 4; ++i) p.alpha[i] = d_signed(r.get(8), 8, kAlphaExp[i]);
  for (std::size_t i = 0; i < 4; ++i) p.beta[i] = d_signed(r.get(8), 8, kBetaExp[i]);
  p.a1_sps = d_signed(r.get(24), 24, -50);
  p.a0_s = d_signed(r.get(32), 32, -30);
  p.tot_s = d_unsigned(r.get(8), 12);
  p.wnt = resolve_week(r.get(8), 256, reference_week);
  p.dt_ls_s = static_cast<int>(sign_extend(r.get(8), 8));
  p.wn_lsf = resolve_week(r.get(8), 256, reference_week);
  p.dn = static_cast<int>(r.get(8));
  p.dt_lsf_s = static_cast<int>(sign_extend(r.get(8), 8));
  return p;
}

std::optional<LnavAlmanacEntry> decode_almanac(const LnavSubframe& words) {
  const int sf = decode_tlm_how(words).subframe_id;
  if ((sf != 4 && sf != 5) || !lnav_parity_ok(words)) return std::nullopt;
  BitReader r(words);
  r.skip(2);
  LnavAlmanacEntry a;
  a.sv_id = static_cast<int>(r.get(6));
  if (a.sv_id < 1 || a.sv_id > 32) return std::nullopt;
  a.e = d_unsigned(r.get(16), -21);
  a.toa_s = d_unsigned(r.get(8), 12);
  a.delta_i_rad = d_sc(r.get(16), 16, -19);
  a.omega_dot_radps = d_sc(r.get(16), 16, -38);
  a.health = static_cast<int>(r.get(8));
  a.sqrt_a_sqrtm = d_unsigned(r.get(24), -11);
  a.omega0_rad = d_sc(r.get(24), 24, -23);
  a.omega_rad = d_sc(r.get(24), 24, -23);
  a.m0_rad = d_sc(r.get(24), 24, -23);
  const std::uint32_t af0_msb = r.get(8);
  a.af1_sps = d_signed(r.get(11), 11, -38);
  a.af0_s = d_signed((af0_msb << 3) | r.get(3), 11, -20);
  return a;
}

std::optional<std::string> decode_special_message(const LnavSubframe& words) {
  if (!is_subframe(words, 4) || decode_page_id(words).sv_id != kSf4SpecialMessage)
    return std::nullopt;
  BitReader r(words);
  r.skip(8);
  std::string msg;
  for (int i = 0; i < 22; ++i) msg.push_back(static_cast<char>(r.get(8)));
  return msg;
}

int lnav_ura_index(double ura_m) {
  // Upper bounds of URA indexes 0..14 (20.3.3.3.1.3).
  constexpr std::array<double, 15> kUpper = {2.40,   3.40,   4.85,   6.85,   9.65,
                                             13.65,  24.00,  48.00,  96.00,  192.00,
                                             384.00, 768.00, 1536.0, 3072.0, 6144.0};
  for (std::size_t i = 0; i < kUpper.size(); ++i)
    if (ura_m <= kUpper[i]) return static_cast<int>(i);
  return 15;
}

double lnav_ura_m(int ura_index) {
  const int n = std::clamp(ura_index, 0, 15);
  if (n <= 6) return std::pow(2.0, 1.0 + n / 2.0);
  if (n < 15) return std::ldexp(1.0, n - 2);
  return 6144.0;
}

LnavAlmanacEntry lnav_almanac_from_ephemeris(const LnavEphemeris& eph, double toa_s, int toa_week) {
  constexpr double kMu = 3.986005e14;  // m^3/s^2 (Table 20-IV)
  constexpr double kHalfWeek = 302400.0;
  auto since = [&](double t_s) {  // toa minus a time of eph.week's neighbourhood
    double dt = (toa_week - eph.week) * 604800.0 + toa_s - t_s;
    while (dt > kHalfWeek) dt -= 604800.0;
    while (dt < -kHalfWeek) dt += 604800.0;
    return dt;
  };
  const double dt_e = since(eph.toe_s);
  const double dt_c = since(eph.toc_s);
  const double a = eph.sqrt_a_sqrtm * eph.sqrt_a_sqrtm;
  const double n = (a > 0.0 ? std::sqrt(kMu / (a * a * a)) : 0.0) + eph.delta_n_radps;

  LnavAlmanacEntry alm;
  alm.sv_id = eph.sv_id;
  alm.e = eph.e;
  alm.toa_s = toa_s;
  alm.delta_i_rad = eph.i0_rad + eph.idot_radps * dt_e - 0.30 * kGpsPi;
  alm.omega_dot_radps = eph.omega_dot_radps;
  const auto h6 = static_cast<std::uint32_t>(std::clamp(eph.health, 0, 63));
  alm.health = static_cast<int>(((h6 & 0x20u) != 0 ? 0xE0u : 0u) | (h6 & 0x1Fu));
  alm.sqrt_a_sqrtm = eph.sqrt_a_sqrtm;
  alm.omega0_rad = eph.omega0_rad + eph.omega_dot_radps * dt_e;
  alm.omega_rad = eph.omega_rad;
  alm.m0_rad = eph.m0_rad + n * dt_e;
  alm.af0_s = eph.af0_s + eph.af1_sps * dt_c + eph.af2_sps2 * dt_c * dt_c;
  alm.af1_sps = eph.af1_sps + 2.0 * eph.af2_sps2 * dt_c;
  alm.anti_spoof_flag = eph.anti_spoof_flag;
  return alm;
}

}  // namespace navemu::lnav
