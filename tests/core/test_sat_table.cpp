// Per-satellite tables (core/sat_table.hpp): one slot for every satellite number the systems
// define, entries made on first use, iteration in SatId order.

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "core/sat_table.hpp"

namespace navemu {
namespace {

TEST(SatTable, HoldsEveryNumberTheSystemsDefine) {
  // GPS 63, SBAS 39 (PRN 120-158), Galileo 36, BeiDou 63, QZSS 10, GLONASS 32, NavIC 14.
  EXPECT_EQ(kDefinedSatellites, 63u + 39u + 36u + 63u + 10u + 32u + 14u);
  SatTable<int> t;
  for (const GnssSystemInfo& s : kGnssSystems)
    for (int n = s.first_number; n <= s.last_number; ++n) t.try_emplace(SatId(s.system, n), n);
  std::size_t count = 0;
  t.for_each([&](SatId, int&) { ++count; });
  EXPECT_EQ(count, kDefinedSatellites);
}

TEST(SatTable, EntriesMadeOnceFoundAndErased) {
  SatTable<double> t;
  const SatId e11(GnssSystem::kGalileo, 11);
  EXPECT_EQ(t.find(e11), nullptr);
  auto [v, fresh] = t.try_emplace(e11, 2.5);
  EXPECT_TRUE(fresh);
  EXPECT_EQ(v, 2.5);
  auto [again, fresh_again] = t.try_emplace(e11, 9.0);
  EXPECT_FALSE(fresh_again);
  EXPECT_EQ(again, 2.5);
  ASSERT_NE(t.find(e11), nullptr);
  EXPECT_EQ(t.find(gps_sat(11)), nullptr) << "GPS PRN 11 is another satellite";
  t.erase(e11);
  EXPECT_EQ(t.find(e11), nullptr);
  t.try_emplace(gps_sat(3), 1.0);
  t.clear();
  EXPECT_EQ(t.find(gps_sat(3)), nullptr);
}

TEST(SatTable, NumbersTheSystemDoesNotDefine) {
  SatTable<int> t;
  EXPECT_EQ(t.find(gps_sat(64)), nullptr);
  EXPECT_EQ(t.find(SatId(GnssSystem::kSbas, 19)), nullptr);
  EXPECT_THROW(t.try_emplace(gps_sat(64)), std::out_of_range);
  EXPECT_THROW(t.try_emplace(SatId(GnssSystem::kQzss, 11)), std::out_of_range);
  t.erase(gps_sat(0));  // nothing to erase
}

TEST(SatTable, IteratesInSatIdOrder) {
  SatTable<int> t;
  const SatId r02(GnssSystem::kGlonass, 2), s20(GnssSystem::kSbas, 20), i14(GnssSystem::kNavic, 14);
  for (SatId s : {r02, gps_sat(30), s20, gps_sat(2), i14}) t.try_emplace(s, 0);
  std::vector<SatId> out;
  t.for_each([&](SatId s, int&) { out.push_back(s); });
  EXPECT_EQ(out, (std::vector<SatId>{gps_sat(2), gps_sat(30), s20, r02, i14}));
}

}  // namespace
}  // namespace navemu
