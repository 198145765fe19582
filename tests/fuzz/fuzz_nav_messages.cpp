// The decoders of the broadcast navigation messages in their u-blox RXM-SFRBX form: GPS/QZSS
// LNAV (protocols/gps_lnav.hpp), Galileo I/NAV (galileo_inav.hpp), GLONASS strings
// (glonass_nav.hpp) and BeiDou D1/D2 (beidou_nav.hpp), as a client decoding a receiver's
// subframes meets them. The input is a stream of records, each one message's words without the
// UBX framing (whose checksum would hide the words from the fuzzer): gnssId (1 byte), the
// number of words (1 byte, at most 16) and the words (little-endian). Each record goes through
// its system's checks and single-unit decoders, and with the units before it through the
// decoders that take several (ephemerides, system data, almanac pairs). Properties besides
// "no crash": an I/NAV page that decodes re-encodes to a page that decodes the same, and a
// GLONASS string that glonass_correct() repairs passes the Hamming check.

#include <array>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <map>
#include <vector>

#include "protocols/beidou_nav.hpp"
#include "protocols/galileo_inav.hpp"
#include "protocols/glonass_nav.hpp"
#include "protocols/gps_lnav.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

using namespace navemu;

constexpr std::size_t kKept = 15;  // units kept per system (a GLONASS frame, 10 D2 pages)

template <typename T>
void keep(std::deque<T>& d, const T& unit) {
  d.push_back(unit);
  if (d.size() > kKept) d.pop_front();
}

void lnav_record(std::span<const std::uint32_t> w, std::deque<lnav::LnavSubframe>& kept) {
  if (w.size() != 10) return;
  lnav::LnavSubframe sf{};
  std::copy(w.begin(), w.end(), sf.begin());
  (void)lnav::lnav_parity_ok(sf);
  (void)lnav::lnav_as_transmitted(sf);
  (void)lnav::decode_tlm_how(sf);
  (void)lnav::decode_page_id(sf);
  (void)lnav::decode_iono_utc(sf);
  (void)lnav::decode_almanac(sf);
  (void)lnav::decode_special_message(sf);
  keep(kept, sf);
  if (kept.size() >= 3)
    (void)lnav::decode_ephemeris(kept[kept.size() - 3], kept[kept.size() - 2], kept.back());
}

void inav_record(std::span<const std::uint32_t> w, std::map<int, inav::InavWord>& by_type) {
  (void)inav::inav_crc_ok(w);
  const std::optional<inav::InavDecodedPage> page = inav::decode_inav_page(w);
  if (!page) return;
  // The page rebuilt from what was decoded decodes to the same word and bits, and rebuilds to
  // itself (the tails and padding, outside the CRC, are rebuilt as zeros).
  const inav::InavPage again = inav::inav_page_from_word(page->word, 0.0, page->extras);
  const std::optional<inav::InavDecodedPage> back = inav::decode_inav_page(again);
  if (!back || back->word != page->word || inav::inav_page_from_word(back->word, 0.0, back->extras) != again)
    std::abort();
  GalileoEphemeris eph;
  inav::InavSystemData sys;
  int week = 0;
  double tow_s = 0.0;
  (void)inav::decode_word_into(page->word, 1100, eph, sys, &week, &tow_s);
  by_type[page->word_type] = page->word;
  const auto has = [&](int t) { return by_type.count(t) > 0; };
  if (has(1) && has(2) && has(3) && has(4) && has(5))
    (void)inav::decode_ephemeris(by_type[1], by_type[2], by_type[3], by_type[4], by_type[5]);
  if (has(5) && has(6) && has(10)) (void)inav::decode_system_data(by_type[5], by_type[6], by_type[10]);
}

void gnav_record(std::span<const std::uint32_t> w, std::deque<gnav::GnavString>& kept) {
  if (w.size() != 4) return;
  const gnav::GnavString s{w[0], w[1], w[2], w[3]};
  (void)gnav::glonass_hamming(s);
  if (const std::optional<gnav::GnavString> fixed = gnav::glonass_correct(s))
    if (gnav::glonass_hamming(*fixed).status != gnav::GnavHamming::kOk) std::abort();  // no error left
  (void)gnav::glonass_string_number(s);
  (void)gnav::decode_ublox_tag(s);
  (void)gnav::decode_l_n(s);
  (void)gnav::decode_system_data(s);
  keep(kept, s);
  const std::size_t n = kept.size();
  if (n >= 2) (void)gnav::decode_almanac(kept[n - 2], kept[n - 1]);
  if (n >= 3) (void)gnav::decode_system_data(kept[n - 3], kept[n - 2], kept[n - 1]);
  if (n >= 5) {
    const GpsTime reference = from_week_tow(2111, 345600.0);
    (void)gnav::decode_ephemeris(kept[n - 5], kept[n - 4], kept[n - 3], kept[n - 2], 18, reference,
                                 gnav::decode_system_data(kept[n - 1]).has_value() ? std::optional<int>(7) : std::nullopt);
    (void)gnav::decode_ephemeris(kept[n - 4], kept[n - 3], kept[n - 2], kept[n - 1], 18, reference);
  }
}

void bds_record(std::span<const std::uint32_t> w, std::deque<bdnav::BdsSubframe>& kept) {
  const std::optional<bdnav::BdsSubframe> sf = bdnav::subframe_from_words(w);
  if (!sf) return;
  (void)bdnav::bch_ok(*sf);
  (void)bdnav::decode_header(*sf, bdnav::NavType::kD1);
  (void)bdnav::decode_header(*sf, bdnav::NavType::kD2);
  (void)bdnav::decode_d1_iono(*sf);
  (void)bdnav::decode_d2_iono(*sf);
  (void)bdnav::decode_d1_time_offsets(*sf);
  (void)bdnav::decode_d1_utc(*sf);
  (void)bdnav::decode_d1_almanac(*sf);
  (void)bdnav::decode_d1_health(*sf);
  keep(kept, *sf);
  const std::size_t n = kept.size();
  if (n >= 3) (void)bdnav::decode_d1_ephemeris(kept[n - 3], kept[n - 2], kept[n - 1], 11);
  if (n >= 10) {
    const std::vector<bdnav::BdsSubframe> pages(kept.end() - 10, kept.end());
    (void)bdnav::decode_d2_ephemeris(pages, 1);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::deque<lnav::LnavSubframe> lnav_kept;
  std::map<int, inav::InavWord> inav_words;
  std::deque<gnav::GnavString> gnav_kept;
  std::deque<bdnav::BdsSubframe> bds_kept;
  std::vector<std::uint32_t> words;
  std::size_t at = 0;
  while (at + 2 <= size) {
    const int gnss_id = data[at];
    const std::size_t n = std::min<std::size_t>(data[at + 1], 16);
    at += 2;
    words.clear();
    for (std::size_t k = 0; k < n && at + 4 <= size; ++k, at += 4)
      words.push_back(static_cast<std::uint32_t>(data[at]) | static_cast<std::uint32_t>(data[at + 1]) << 8 |
                      static_cast<std::uint32_t>(data[at + 2]) << 16 | static_cast<std::uint32_t>(data[at + 3]) << 24);
    switch (gnss_id) {
      case 0:
      case 5: lnav_record(words, lnav_kept); break;
      case 2: inav_record(words, inav_words); break;
      case 3: bds_record(words, bds_kept); break;
      case 6: gnav_record(words, gnav_kept); break;
      default: break;
    }
  }
  return 0;
}
