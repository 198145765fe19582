#pragma once
// The real RXM-SFRBX of the u-blox captures in ../shared/data/receiver_logs, for the tests of
// the navigation message encoders and decoders (test_lnav, test_galileo_inav,
// test_glonass_nav, test_beidou_nav). A minimal UBX scanner: sync B5 62, class, id, u16
// length, payload, Fletcher checksum (frames failing it are skipped).
//
// tests/test_support.hpp pulls in the models, which the protocols' test executable does not
// link, so the lookup of ../shared is its own: $NAVEMU_SHARED, else the directory next to the
// repository.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "core/time.hpp"

namespace navemu::test {

inline std::filesystem::path shared_file(const std::string& relative) {
  const char* env = std::getenv("NAVEMU_SHARED");
  const std::filesystem::path shared = env != nullptr ? env : NAVEMU_SHARED_DEFAULT;
  return shared / "data" / relative;
}

#define REQUIRE_SHARED_FILE(rel)                                                                 \
  do {                                                                                           \
    if (!std::filesystem::is_regular_file(::navemu::test::shared_file(rel)))                     \
      GTEST_SKIP() << ::navemu::test::shared_file(rel) << " not found (set NAVEMU_SHARED): skipped"; \
  } while (0)

struct Sfrbx {
  int gnss_id = 0;
  int sv_id = 0;
  int sig_id = 0;
  int freq_id = 0;
  int num_words = 0;
  std::vector<std::uint32_t> words;
  std::optional<GpsTime> time;  // of the NAV-TIMEGPS before it
};

// Every RXM-SFRBX of a capture, in order, with the time of the NAV-TIMEGPS before it.
inline std::vector<Sfrbx> read_sfrbx(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<std::uint8_t> b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto u4 = [&](std::size_t at) {
    return static_cast<std::uint32_t>(b[at]) | (static_cast<std::uint32_t>(b[at + 1]) << 8) |
           (static_cast<std::uint32_t>(b[at + 2]) << 16) | (static_cast<std::uint32_t>(b[at + 3]) << 24);
  };
  std::vector<Sfrbx> out;
  std::optional<GpsTime> now;
  std::size_t i = 0;
  while (i + 8 <= b.size()) {
    if (b[i] != 0xB5 || b[i + 1] != 0x62) {
      ++i;
      continue;
    }
    const std::size_t len = static_cast<std::size_t>(b[i + 4]) | (static_cast<std::size_t>(b[i + 5]) << 8);
    if (i + 8 + len > b.size()) break;
    std::uint8_t ck_a = 0;
    std::uint8_t ck_b = 0;
    for (std::size_t k = i + 2; k < i + 6 + len; ++k) {
      ck_a = static_cast<std::uint8_t>(ck_a + b[k]);
      ck_b = static_cast<std::uint8_t>(ck_b + ck_a);
    }
    if (ck_a != b[i + 6 + len] || ck_b != b[i + 7 + len]) {
      ++i;
      continue;
    }
    const std::size_t p = i + 6;
    if (b[i + 2] == 0x01 && b[i + 3] == 0x20 && len >= 16) {  // NAV-TIMEGPS: iTOW ms, week
      const int week = static_cast<int>(b[p + 8]) | (static_cast<int>(b[p + 9]) << 8);
      now = from_week_tow(week, static_cast<double>(u4(p)) * 1e-3);
    }
    if (b[i + 2] == 0x02 && b[i + 3] == 0x13 && len >= 8) {  // RXM-SFRBX
      Sfrbx s;
      s.gnss_id = b[p];
      s.sv_id = b[p + 1];
      s.sig_id = b[p + 2];
      s.freq_id = b[p + 3];
      s.num_words = b[p + 4];
      for (std::size_t w = 0; w < static_cast<std::size_t>(s.num_words) && 8 + 4 * w + 4 <= len; ++w)
        s.words.push_back(u4(p + 8 + 4 * w));
      s.time = now;
      out.push_back(s);
    }
    i += 8 + len;
  }
  return out;
}

// Those of one system (gnssId).
inline std::vector<Sfrbx> read_sfrbx(const std::filesystem::path& path, int gnss_id) {
  std::vector<Sfrbx> out;
  for (Sfrbx& s : read_sfrbx(path))
    if (s.gnss_id == gnss_id) out.push_back(std::move(s));
  return out;
}

}  // namespace navemu::test
