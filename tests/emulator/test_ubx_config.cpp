// The layered configuration database of a generation-9 u-blox part, against the semantics the
// ZED-F9P interface description gives (UBX-18010854, 6.2 "Configuration layers", 6.3
// "Configuration interface access", 6.6 "Configuration reset behavior", and the UBX-CFG-VALSET /
// VALGET / VALDEL / CFG sections).

#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <set>
#include <vector>

#include "emulator/ubx_config.hpp"
#include "protocols/ubx_config_db.hpp"

namespace navemu {
namespace {

using ubx::CfgKeyValue;

constexpr std::uint32_t kMeas = 0x30210001;     // CFG-RATE-MEAS, U2 ms, 25..65535, default 1000
constexpr std::uint32_t kNav = 0x30210002;      // CFG-RATE-NAV, U2, 1..128, default 1
constexpr std::uint32_t kTimeref = 0x20210003;  // CFG-RATE-TIMEREF, E1, default 1 (GPS)
constexpr std::uint32_t kDynmodel = 0x20110021; // CFG-NAVSPG-DYNMODEL, E1, default 0 (portable)
constexpr std::uint32_t kTp1Period = 0x40050002;  // CFG-TP-PERIOD_TP1, U4 us, default 1000000
constexpr std::uint32_t kUnknown = 0x40fe0002;    // group 0xfe is assigned to nothing

UbxConfig f9p() { return UbxConfig(ubx::kFwHpg113, {}); }

ubx::CfgValset set(std::uint8_t layers, std::vector<CfgKeyValue> values, std::uint8_t transaction = 0) {
  ubx::CfgValset m;
  m.version = transaction == 0 ? 0 : 1;
  m.layers = layers;
  m.transaction = transaction;
  m.values = std::move(values);
  return m;
}

// One item read from a layer; none when the part answers ACK-NAK.
std::optional<std::uint64_t> get(const UbxConfig& c, std::uint32_t key, std::uint8_t layer = ubx::kLayerRam) {
  ubx::CfgValgetRequest q;
  q.layer = layer;
  q.keys = {key};
  const auto r = c.valget(q);
  if (!r || r->values.size() != 1 || r->values[0].key_id != key) return std::nullopt;
  return r->values[0].value;
}

const std::uint8_t kRam = ubx::kLayerMaskRam, kBbr = ubx::kLayerMaskBbr, kFlash = ubx::kLayerMaskFlash;

// 6.2: the Default layer holds the part's values; RAM starts from them.
TEST(UbxConfig, PowerUpRunsOnThePartsDefaults) {
  const UbxConfig c = f9p();
  EXPECT_EQ(get(c, kMeas), 1000u);
  EXPECT_EQ(get(c, kMeas, ubx::kLayerDefault), 1000u);
  EXPECT_EQ(get(c, kTp1Period), 1'000'000u);
  EXPECT_FALSE(get(c, kMeas, ubx::kLayerBbr)) << "nothing stored in BBR: nothing to answer, ACK-NAK";
  EXPECT_FALSE(get(c, kUnknown)) << "a key the part does not have: ACK-NAK";
  // A profile's own defaults replace the part's in the Default layer.
  const std::pair<std::uint32_t, std::uint64_t> profile[] = {{kMeas, 200}};
  const UbxConfig p(ubx::kFwHpg113, profile);
  EXPECT_EQ(get(p, kMeas), 200u);
  EXPECT_EQ(get(p, kMeas, ubx::kLayerDefault), 200u);
}

// 6.6: at reset, RAM is rebuilt from Default, then Flash, then BBR over it: RAM-only values are
// lost, BBR wins over Flash. VALDEL removes a layer's value so that the next one shows through.
TEST(UbxConfig, ResetKeepsBbrAndFlashValuesAndDropsRamOnes) {
  UbxConfig c = f9p();
  ASSERT_TRUE(c.valset(set(kRam, {{kMeas, 200}})));
  ASSERT_TRUE(c.valset(set(kFlash, {{kTp1Period, 300'000}, {kDynmodel, 4}})));
  ASSERT_TRUE(c.valset(set(kBbr, {{kTp1Period, 400'000}})));
  EXPECT_EQ(get(c, kMeas), 200u);
  EXPECT_EQ(get(c, kTp1Period), 1'000'000u) << "BBR and Flash only: RAM unchanged until reset";
  EXPECT_EQ(get(c, kTp1Period, ubx::kLayerFlash), 300'000u);
  EXPECT_EQ(get(c, kTp1Period, ubx::kLayerBbr), 400'000u);

  c.reload();
  EXPECT_EQ(get(c, kMeas), 1000u);
  EXPECT_EQ(get(c, kTp1Period), 400'000u);
  EXPECT_EQ(get(c, kDynmodel), 4u);

  ubx::CfgValdel del;
  del.layers = kBbr;
  del.keys = {kTp1Period};
  ASSERT_TRUE(c.valdel(del));
  c.reload();
  EXPECT_EQ(get(c, kTp1Period), 300'000u);
  del.layers = kFlash;
  del.keys = {0x0011ffff};  // the whole CFG-NAVSPG group
  ASSERT_TRUE(c.valdel(del));
  del.keys = {kTp1Period};
  ASSERT_TRUE(c.valdel(del));
  ASSERT_TRUE(c.valdel(del)) << "deleting what is not stored is no error";
  c.reload();
  EXPECT_EQ(get(c, kTp1Period), 1'000'000u);
  EXPECT_EQ(get(c, kDynmodel), 0u);
  del.keys = {kUnknown};
  EXPECT_FALSE(c.valdel(del));
}

// UBX-CFG-CFG: save copies RAM into the chosen devices, clear empties them, load rebuilds RAM.
TEST(UbxConfig, SaveClearAndLoad) {
  UbxConfig c = f9p();
  ASSERT_TRUE(c.valset(set(kRam, {{kMeas, 250}, {kDynmodel, 4}})));
  c.save(0x02);  // Flash
  ASSERT_TRUE(c.valset(set(kRam, {{kMeas, 500}})));
  c.load();
  EXPECT_EQ(get(c, kMeas), 250u);
  EXPECT_EQ(get(c, kDynmodel), 4u);
  c.clear(0x03);
  c.load();
  EXPECT_EQ(get(c, kMeas), 1000u);
  EXPECT_EQ(get(c, kDynmodel), 0u);
}

// UBX-CFG-VALSET: values are checked against their range when RAM is written; one bad value or
// one unknown key and nothing of the message is applied.
TEST(UbxConfig, ValsetIsAllOrNothing) {
  UbxConfig c = f9p();
  const std::uint64_t g = c.generation();
  EXPECT_FALSE(c.valset(set(kRam, {{kNav, 2}, {kMeas, 20}})));  // 20 ms < 25 ms
  EXPECT_FALSE(c.valset(set(kRam, {{kNav, 2}, {kUnknown, 1}})));
  EXPECT_FALSE(c.valset(set(0, {{kNav, 2}}))) << "no layer";
  EXPECT_EQ(get(c, kNav), 1u);
  EXPECT_EQ(c.generation(), g) << "nothing changed";
  EXPECT_TRUE(c.valset(set(kRam, {{kNav, 2}, {kNav, 3}})));
  EXPECT_EQ(get(c, kNav), 3u) << "a key given twice: the last value counts";
  EXPECT_GT(c.generation(), g);
  std::vector<CfgKeyValue> many(65, CfgKeyValue{kNav, 4});
  EXPECT_FALSE(c.valset(set(kRam, many))) << "at most 64 items per message";
}

// UBX-CFG-VALSET version 1 transactions: nothing is applied before "apply"; an error or a change
// of layers cancels the transaction, and "apply" without one is refused.
TEST(UbxConfig, TransactionsApplyAtTheEndOrNotAtAll) {
  UbxConfig c = f9p();
  ASSERT_TRUE(c.valset(set(kRam, {{kMeas, 200}}, 1)));
  ASSERT_TRUE(c.valset(set(kRam, {{kNav, 2}}, 2)));
  EXPECT_EQ(get(c, kMeas), 1000u) << "not applied before the end";
  ASSERT_TRUE(c.valset(set(kRam, {{kTimeref, 0}}, 3)));
  EXPECT_EQ(get(c, kMeas), 200u);
  EXPECT_EQ(get(c, kNav), 2u);
  EXPECT_EQ(get(c, kTimeref), 0u);

  ASSERT_TRUE(c.valset(set(kRam, {{kMeas, 500}}, 1)));
  EXPECT_FALSE(c.valset(set(kRam, {{kUnknown, 1}}, 2)));
  EXPECT_FALSE(c.valset(set(kRam, {{kNav, 4}}, 3))) << "the transaction was cancelled";
  EXPECT_EQ(get(c, kMeas), 200u);
  EXPECT_EQ(get(c, kNav), 2u);

  ASSERT_TRUE(c.valset(set(kRam, {{kMeas, 500}}, 1)));
  EXPECT_FALSE(c.valset(set(kRam | kBbr, {{kNav, 4}}, 2))) << "layers changed within a transaction";
  ASSERT_TRUE(c.valset(set(kRam, {{kMeas, 500}}, 1)));
  c.cancel_transaction();  // another CFG message
  EXPECT_FALSE(c.valset(set(kRam, {{kNav, 4}}, 3)));
  EXPECT_EQ(get(c, kMeas), 200u);
}

// UBX-CFG-VALGET: a group wildcard (item ID 0xffff) names every item of the group; the answer
// holds at most 64 items, `position` pages through the rest.
TEST(UbxConfig, ValgetWildcardsAndPaging) {
  const UbxConfig c = f9p();
  ubx::CfgValgetRequest q;
  q.keys = {0x0021ffff};  // CFG-RATE-*
  auto r = c.valget(q);
  ASSERT_TRUE(r);
  std::set<std::uint32_t> rate;
  for (const CfgKeyValue& kv : r->values) rate.insert(kv.key_id);
  EXPECT_TRUE(rate.count(kMeas) && rate.count(kNav) && rate.count(kTimeref));
  for (std::uint32_t k : rate) EXPECT_EQ((k >> 16) & 0xff, 0x21u);

  q.keys = {0x0fffffff};  // every item
  std::set<std::uint32_t> seen;
  std::size_t pages = 0;
  for (q.position = 0;; q.position = static_cast<std::uint16_t>(q.position + 64)) {
    r = c.valget(q);
    if (!r) break;
    ASSERT_LE(r->values.size(), 64u);
    for (const CfgKeyValue& kv : r->values) EXPECT_TRUE(seen.insert(kv.key_id).second) << kv.key_id;
    ++pages;
  }
  std::size_t items = 0;
  for (const ubx::CfgKey& k : ubx::config_keys()) items += (k.firmware & ubx::kFwHpg113) ? 1 : 0;
  EXPECT_EQ(seen.size(), items) << "every item once over " << pages << " pages";
  EXPECT_GT(pages, 10u);
}

}  // namespace
}  // namespace navemu
