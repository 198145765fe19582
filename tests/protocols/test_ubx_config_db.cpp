// The generation-9 configuration database (protocols/ubx_config_db.*) against an independent
// copy (gpsd's ubxtool key table, python3-gps), against its own invariants (interface
// description "Configuration item key ID"), and against published values.
#include "protocols/ubx_config_db.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace navemu::ubx {
namespace {

std::size_t type_size(CfgType t) {
  switch (t) {
    case CfgType::kL: case CfgType::kU1: case CfgType::kI1: case CfgType::kE1: case CfgType::kX1:
      return 1;
    case CfgType::kU2: case CfgType::kI2: case CfgType::kE2: case CfgType::kX2: return 2;
    case CfgType::kU4: case CfgType::kI4: case CfgType::kE4: case CfgType::kX4: case CfgType::kR4:
      return 4;
    case CfgType::kU8: case CfgType::kI8: case CfgType::kX8: case CfgType::kR8: return 8;
  }
  return 0;
}

std::string type_name(CfgType t) {
  static const char* const kNames[] = {"L",  "U1", "U2", "U4", "U8", "I1", "I2", "I4", "I8",
                                       "E1", "E2", "E4", "X1", "X2", "X4", "X8", "R4", "R8"};
  return kNames[static_cast<int>(t)];
}

// ---- the independent copy: ubxtool's table -----------------------------------------------

struct UbxtoolKey {
  std::uint32_t id;
  std::string type;
};

// ubxtool's configuration table (gps/ubx.py, class ubx, `cfgs`: name, key ID, type, scale,
// unit, description), read through the installed python3-gps. Empty when it cannot be read.
std::map<std::string, UbxtoolKey> read_ubxtool_table() {
  std::map<std::string, UbxtoolKey> table;
  FILE* p = ::popen(
      "/usr/bin/python3 -c 'import gps.ubx as u\n"
      "for c in u.ubx.cfgs:\n"
      "    print(c[0], c[1], c[2] or \"-\")' 2>/dev/null",
      "r");
  if (p == nullptr) return table;
  char line[256];
  while (std::fgets(line, sizeof line, p) != nullptr) {
    std::istringstream in(line);
    std::string name, type;
    unsigned long long id = 0;
    if (in >> name >> id >> type && type != "-") table[name] = {static_cast<std::uint32_t>(id), type};
  }
  ::pclose(p);
  return table;
}

// ubxtool keys whose ID differs from ours, where the interface description (HPG 1.13
// extraction, CFG-MSGOUT table) and pyubx2 agree with each other and with our table: the port
// order I2C, UART1, UART2, USB, SPI = ID +0..+4 of every other message is kept for these two
// as well; ubxtool 3.22 swaps the ports of NAV-TIMEQZSS and gives NAV-SLAS on USB the ID of
// NAV-SIG on USB (0x20910348).
const std::set<std::string> kUbxtoolIdErrata = {
    "CFG-MSGOUT-UBX_NAV_SLAS_UART1",     "CFG-MSGOUT-UBX_NAV_SLAS_UART2",
    "CFG-MSGOUT-UBX_NAV_SLAS_USB",       "CFG-MSGOUT-UBX_NAV_TIMEQZSS_UART1",
    "CFG-MSGOUT-UBX_NAV_TIMEQZSS_UART2", "CFG-MSGOUT-UBX_NAV_TIMEQZSS_USB"};

// ubxtool keys the ZED-F9P HPG 1.13 / 1.32 interface descriptions do not have, by group or
// name prefix, with the product they belong to.
const std::vector<std::pair<std::string, std::string>> kNotOnF9p = {
    {"CFG-ANA-", "AssistNow Autonomous: M9/M10 (no CFG-ANA group in the F9P descriptions)"},
    {"CFG-BATCH-", "data batching: M9/M10"},
    {"CFG-PM-", "power management: M9/M10/F9R"},
    {"CFG-TP-", "second time pulse (_TP2): F9T/M9; the ZED-F9P has one TIMEPULSE (TP1 keys only)"},
    {"CFG-NAVSPG-USE_PPP", "M9 SPG"},
    {"CFG-NAVSPG-SIGATTCOMP", "M9/M10 signal attenuation compensation"},
    {"CFG-UART2-REMAP", "M9 pin remap"},
    {"RTCM2X", "RTCM 2 input: u-blox M8/M9, not in the F9P descriptions"},
    {"CFG-MSGOUT-UBX_NAV_AOPSTATUS", "AssistNow Autonomous status: M9/M10"},
    {"CFG-MSGOUT-UBX_TIM_SVIN", "timing survey-in: F9T"},
};

std::string why_not_on_f9p(const std::string& name) {
  for (const auto& [pattern, why] : kNotOnF9p) {
    if (name.find(pattern) != std::string::npos) return why;
  }
  return {};
}

TEST(UbxConfigDb, EveryUbxtoolKeyWeHaveMatchesInIdAndType) {
  const auto ubxtool = read_ubxtool_table();
  if (ubxtool.empty()) GTEST_SKIP() << "/usr/bin/python3 cannot import gps.ubx (python3-gps)";

  std::size_t matched = 0, by_id_only = 0;
  std::vector<std::string> lacking_f9p, lacking_other;
  std::set<std::string> id_mismatch;
  for (const auto& [name, uk] : ubxtool) {
    const CfgKey* k = find_config_key(name);
    if (k == nullptr) {
      if (const CfgKey* same_id = find_config_key(uk.id); same_id != nullptr) {
        // The same key under the interface description's name (ubxtool: CFG-QZSS-USE_TESTMODE).
        EXPECT_EQ(type_name(same_id->type), uk.type) << name << " = " << same_id->name;
        ++by_id_only;
        continue;
      }
      const std::string why = why_not_on_f9p(name);
      (why.empty() ? lacking_f9p : lacking_other).push_back(name + (why.empty() ? "" : " (" + why + ")"));
      continue;
    }
    ++matched;
    EXPECT_EQ(type_name(k->type), uk.type) << name;
    if (k->id != uk.id) id_mismatch.insert(name);
  }
  // Any ID difference outside the documented ubxtool errata is ours to fix.
  EXPECT_EQ(id_mismatch, kUbxtoolIdErrata);
  EXPECT_TRUE(lacking_f9p.empty()) << "ubxtool keys of the F9P we lack: " << lacking_f9p.size();
  for (const auto& n : lacking_f9p) ADD_FAILURE() << "missing: " << n;

  const std::size_t covered = matched + by_id_only;
  const std::size_t f9p_keys = covered + lacking_f9p.size();
  std::printf("ubxtool: %zu keys; we have %zu by name and %zu more by ID (%zu of %zu ubxtool keys"
              " the F9P has, %.1f %%); %zu ID errata of ubxtool; %zu ubxtool keys are of other"
              " products:\n",
              ubxtool.size(), matched, by_id_only, covered, f9p_keys,
              100.0 * static_cast<double>(covered) / static_cast<double>(f9p_keys),
              id_mismatch.size(), lacking_other.size());
  for (const auto& n : lacking_other) std::printf("  %s\n", n.c_str());
  EXPECT_GE(100 * covered, 95 * f9p_keys);
}

// ---- internal consistency -------------------------------------------------------------------

TEST(UbxConfigDb, SizeBitsOfEveryIdAgreeWithItsType) {
  for (const CfgKey& k : config_keys()) {
    EXPECT_EQ(value_size(k.id), type_size(k.type)) << k.name;
    // Size code 1 is reserved for L (one bit stored in a byte), 2 for the other one-byte types.
    EXPECT_EQ(((k.id >> 28) & 7u) == 1u, k.type == CfgType::kL) << k.name;
    EXPECT_EQ(k.id & 0x8f00f000u, 0u) << k.name << ": reserved bits set";
  }
}

TEST(UbxConfigDb, NamesAndIdsAreUniqueAndLookupsFindThem) {
  std::set<std::string_view> names;
  std::set<std::uint32_t> ids;
  for (const CfgKey& k : config_keys()) {
    EXPECT_TRUE(names.insert(k.name).second) << "duplicate name " << k.name;
    EXPECT_TRUE(ids.insert(k.id).second) << "duplicate ID " << k.name;
    EXPECT_EQ(find_config_key(k.name), &k);
    EXPECT_EQ(find_config_key(k.id), &k);
    EXPECT_NE(k.firmware & kFwBoth, 0) << k.name << " is in no firmware";
  }
  EXPECT_EQ(find_config_key(0x30210099u), nullptr);
  EXPECT_EQ(find_config_key("CFG-RATE-NOPE"), nullptr);
}

TEST(UbxConfigDb, DefaultsAreValidValuesOfTheirOwnKey) {
  for (const CfgKey& k : config_keys()) {
    EXPECT_TRUE(value_valid(k, k.default_raw)) << k.name << " default 0x" << std::hex << k.default_raw;
  }
}

TEST(UbxConfigDb, GroupWildcardsCoverExactlyTheirKeys) {
  std::size_t keys_in_groups = 0;
  for (const CfgGroup& g : config_groups()) {
    EXPECT_EQ(find_config_group(g.name), &g);
    const std::string prefix = std::string(g.name) + "-";
    for (const CfgKey& k : config_keys()) {
      const bool named = k.name.starts_with(prefix);
      EXPECT_EQ(key_matches(group_wildcard(g.group_id), k.id), named) << g.name << " / " << k.name;
      keys_in_groups += named ? 1u : 0u;
      EXPECT_TRUE(key_matches(kAllGroupsWildcard, k.id));
    }
  }
  EXPECT_EQ(keys_in_groups, config_keys().size());
  EXPECT_EQ(group_wildcard(0x21), 0x1021ffffu);  // ubxtool's "CFG-RATE" wildcard
  const CfgGroup* rate = find_config_group("CFG-RATE");
  ASSERT_NE(rate, nullptr);
  EXPECT_EQ(rate->group_id, 0x21);
}

TEST(UbxConfigDb, ValueValidChecksWidthRangeAndEnumeration) {
  const CfgKey* dyn = find_config_key("CFG-NAVSPG-DYNMODEL");
  ASSERT_NE(dyn, nullptr);
  EXPECT_TRUE(value_valid(*dyn, 4));    // automotive
  EXPECT_FALSE(value_valid(*dyn, 1));   // no constant 1 in CFG-NAVSPG-DYNMODEL
  EXPECT_FALSE(value_valid(*dyn, 0x104));  // wider than E1
  const CfgKey* meas = find_config_key("CFG-RATE-MEAS");
  ASSERT_NE(meas, nullptr);
  EXPECT_FALSE(value_valid(*meas, 24));  // "The minimum value is 25" (CFG-RATE-MEAS)
  EXPECT_TRUE(value_valid(*meas, 25));
  const CfgKey* hp = find_config_key("CFG-TMODE-LAT_HP");  // I1, "Accepted range is -99 to +99"
  ASSERT_NE(hp, nullptr);
  EXPECT_TRUE(value_valid(*hp, 0x9d));   // -99
  EXPECT_FALSE(value_valid(*hp, 0x9c));  // -100
  const CfgKey* dx = find_config_key("CFG-NAVSPG-USRDAT_DX");  // R4, +/- 5000 m
  ASSERT_NE(dx, nullptr);
  EXPECT_TRUE(value_valid(*dx, std::bit_cast<std::uint32_t>(-4999.5f)));
  EXPECT_FALSE(value_valid(*dx, std::bit_cast<std::uint32_t>(5000.5f)));
  const CfgKey* l = find_config_key("CFG-ITFM-ENABLE");
  ASSERT_NE(l, nullptr);
  EXPECT_TRUE(value_valid(*l, 1));
  EXPECT_FALSE(value_valid(*l, 2));
}

// ---- published values ---------------------------------------------------------------------

struct Published {
  const char* name;
  std::uint32_t id;
  CfgType type;
  std::uint64_t default_raw;
  CfgDefaultSource source;
  const char* where;
};

TEST(UbxConfigDb, PublishedValues) {
  const Published kPublished[] = {
      // Key IDs and types: ZED-F9P interface description, CFG-RATE / CFG-UART1 / CFG-NAVSPG /
      // CFG-MSGOUT / CFG-SIGNAL configuration items. Defaults as noted.
      {"CFG-RATE-MEAS", 0x30210001, CfgType::kU2, 1000, CfgDefaultSource::kGen9Sibling,
       "1000 ms: generation-9 configuration defaults (M9-class interface description)"},
      {"CFG-UART1-BAUDRATE", 0x40520001, CfgType::kU4, 38400, CfgDefaultSource::kGen9Sibling,
       "38400: ZED-F9H integration manual UBX-19030120 section 3.6.1 'The default baud rate is"
       " 38400 baud'; generation-9 configuration defaults"},
      {"CFG-NAVSPG-DYNMODEL", 0x20110021, CfgType::kE1, 0, CfgDefaultSource::kGen9Sibling,
       "0 = PORT (portable): generation-9 configuration defaults"},
      {"CFG-MSGOUT-NMEA_ID_GGA_UART1", 0x209100bb, CfgType::kU1, 1, CfgDefaultSource::kGen9Sibling,
       "1: ZED-F9P integration manual UBX-18010802 R08 appendix 'NMEA messages are enabled by"
       " default on the UART1, I2C, SPI and USB interface'; GGA in the default set of the"
       " generation-9 configuration defaults"},
      {"CFG-SIGNAL-BDS_B2_ENA", 0x1031000e, CfgType::kL, 0, CfgDefaultSource::kF9pDocument,
       "ZED-F9P integration manual UBX-18010802 section 'Default GNSS configuration': 'BDS B2I"
       " is also supported but not enabled in the default GNSS configuration'"},
      {"CFG-SIGNAL-GLO_L2_ENA", 0x1031001a, CfgType::kL, 1, CfgDefaultSource::kF9pDocument,
       "same section: GLO L1OF L2OF enabled"},
  };
  for (const Published& p : kPublished) {
    const CfgKey* k = find_config_key(p.name);
    ASSERT_NE(k, nullptr) << p.name;
    EXPECT_EQ(k->id, p.id) << p.name;
    EXPECT_EQ(k->type, p.type) << p.name;
    EXPECT_EQ(k->default_raw, p.default_raw) << p.name << " (" << p.where << ")";
    EXPECT_EQ(k->default_source, p.source) << p.name;
  }
  // CFG-RATE-MEAS: scale 0.001 s (interface description, CFG-RATE configuration items).
  EXPECT_DOUBLE_EQ(find_config_key("CFG-RATE-MEAS")->scale, 0.001);
  EXPECT_EQ(find_config_key("CFG-RATE-MEAS")->unit, "s");
  // R8 default as IEEE bits: WGS84 semi-major axis 6378137 m (CFG-NAVSPG-USRDAT_MAJA).
  EXPECT_EQ(std::bit_cast<double>(find_config_key("CFG-NAVSPG-USRDAT_MAJA")->default_raw), 6378137.0);
  // Keys of the current firmware only: SPARTN input (HPG 1.30+), jamming detector sensitivity.
  EXPECT_EQ(find_config_key("CFG-UART1INPROT-SPARTN")->firmware, kFwHpg132);
  EXPECT_EQ(find_config_key("CFG-SEC-JAMDET_SENSITIVITY_HI")->firmware, kFwHpg132);
  EXPECT_EQ(find_config_key("CFG-TMODE-MODE")->firmware, kFwBoth);
  // Not a key of the F9P: NAV-SVINFO output (u-blox 8), the second time pulse.
  EXPECT_EQ(find_config_key("CFG-MSGOUT-UBX_NAV_SVINFO_UART1"), nullptr);
  EXPECT_EQ(find_config_key("CFG-TP-PERIOD_TP2"), nullptr);
}

// The keys the issue found a real F9P accepts and navemu NAKed are all here.
TEST(UbxConfigDb, KeysPx4SendsAreKnown) {
  for (std::uint32_t id : {0x20520002u, 0x20520003u, 0x20520004u, 0x10730004u, 0x10770004u,
                           0x20110011u, 0x2011001cu, 0x10220001u, 0x10220002u, 0x10220003u,
                           0x10220004u, 0x20140011u, 0x1041000du, 0x10f60051u, 0x20030001u}) {
    EXPECT_NE(find_config_key(id), nullptr) << std::hex << id;
  }
}

TEST(UbxConfigDb, CountsPerFirmwareAndDefaultSource) {
  std::size_t fw113 = 0, fw132 = 0;
  std::map<CfgDefaultSource, std::size_t> by_source;
  std::size_t no_range = 0;
  for (const CfgKey& k : config_keys()) {
    fw113 += key_in_firmware(k, kFwHpg113) ? 1u : 0u;
    fw132 += key_in_firmware(k, kFwHpg132) ? 1u : 0u;
    ++by_source[k.default_source];
    no_range += (k.range.kind == CfgRangeKind::kAny && k.type != CfgType::kL) ? 1u : 0u;
  }
  std::printf("keys: %zu (HPG 1.13: %zu, HPG 1.32: %zu, groups %zu); defaults from an F9P document"
              " %zu, from a generation-9 sibling %zu, unestablished %zu; %zu non-L keys without a"
              " documented range\n",
              config_keys().size(), fw113, fw132, config_groups().size(),
              by_source[CfgDefaultSource::kF9pDocument], by_source[CfgDefaultSource::kGen9Sibling],
              by_source[CfgDefaultSource::kUnestablished], no_range);
  EXPECT_GT(fw132, fw113);
}

}  // namespace
}  // namespace navemu::ubx
