#pragma once
// The generation-9 configuration database of the ZED-F9P: every configuration item (key) of
// the interface description as one row of data (protocols/ubx_config_db_table.inc), with its
// key ID, type, scale and unit, default value, valid values and the firmware that has it.
//
// Sources (per group and per field in docs/ubx_config_db_sources.md): u-blox ZED-F9P
// Interface Description UBX-18010854 R08 / u-blox F9 HPG 1.13 Interface Description
// UBX-21023318 (protocol 27.12) and u-blox F9 HPG 1.32 Interface Description UBX-22008968
// (protocol 27.31), section "Configuration interface" / "Configuration reference"; key IDs
// and types cross-checked between pyubx2 (ubxtypes_configdb.py), per-manual extractions of
// the two descriptions and u-blox's ubxlib; gpsd's ubxtool table is the independent check in
// tests/protocols/test_ubx_config_db.cpp.
//
// Key ID layout (interface description, "Configuration items" / "Configuration item key
// ID"): bits 0..11 item ID, bits 16..23 group ID, bits 28..30 the value size (1: one bit
// stored in a byte (type L), 2: one byte, 3: two bytes, 4: four bytes, 5: eight bytes).
// Wildcards for CFG-VALGET/VALDEL: item ID 0xfff = every item of the group, group ID 0xff =
// every group.

#include <cstdint>
#include <initializer_list>
#include <span>
#include <string_view>

namespace navemu::ubx {

enum class CfgType : std::uint8_t {
  kL, kU1, kU2, kU4, kU8, kI1, kI2, kI4, kI8, kE1, kE2, kE4, kX1, kX2, kX4, kX8, kR4, kR8
};

// Firmware versions a key exists in (bit mask).
inline constexpr std::uint8_t kFwHpg113 = 1;  // HPG 1.13, protocol 27.12
inline constexpr std::uint8_t kFwHpg132 = 2;  // HPG 1.32, protocol 27.31
inline constexpr std::uint8_t kFwBoth = kFwHpg113 | kFwHpg132;

// Where a row's default value comes from.
enum class CfgDefaultSource : std::uint8_t {
  kF9pDocument,    // stated in an F9P document (interface description or integration manual)
  kGen9Sibling,    // the configuration defaults of another u-blox generation-9 receiver's
                   // interface description (same configuration database); not yet confirmed
                   // for the F9P
  kUnestablished,  // no source found: the value is a placeholder (0, or the smallest valid value)
};

// Valid values of a key. kAny: every value the type can hold (no documented range; L: 0 or 1).
enum class CfgRangeKind : std::uint8_t { kAny, kMinMax, kEnum };
struct CfgRange {
  CfgRangeKind kind;
  double min;                   // kMinMax: inclusive bounds in raw units (unscaled)
  double max;
  std::uint64_t allowed_mask;   // kEnum: bit v set = value v documented (values 0..63)
};

struct CfgKey {
  std::string_view name;        // "CFG-RATE-MEAS"
  std::uint32_t id;             // 0x30210001
  CfgType type;
  double scale;                 // physical value = raw * scale, in `unit`
  std::string_view unit;
  std::uint64_t default_raw;    // the value as sent on the wire (little-endian, value_size()
                                // bytes; two's complement; IEEE bits for R4/R8)
  CfgRange range;
  std::uint8_t firmware;        // kFwHpg113 | kFwHpg132
  CfgDefaultSource default_source;
};

// A configuration group: the group byte (bits 16..23) shared by the keys CFG-<name>-*.
struct CfgGroup {
  std::string_view name;        // "CFG-RATE"
  std::uint8_t group_id;        // 0x21
};

std::span<const CfgKey> config_keys();
std::span<const CfgGroup> config_groups();
const CfgKey* find_config_key(std::uint32_t id);
const CfgKey* find_config_key(std::string_view name);
const CfgGroup* find_config_group(std::string_view name);

// Bytes of the value of key `id`, from its size bits 28..30; 0 for a reserved size code.
std::size_t value_size(std::uint32_t id);

// Group wildcard key (item ID 0xfff) of a group, with the size bits of a one-byte key, as
// ubxtool and u-center send it: 0x1021ffff for CFG-RATE... (the size bits are ignored on match).
constexpr std::uint32_t group_wildcard(std::uint8_t group_id) {
  return 0x1000ffffu | (std::uint32_t{group_id} << 16);
}
inline constexpr std::uint32_t kAllGroupsWildcard = 0x0fffffffu;

// True when `query` (a key ID or a wildcard) selects the key `id`.
constexpr bool key_matches(std::uint32_t query, std::uint32_t id) {
  const std::uint32_t query_group = (query >> 16) & 0xffu;
  const std::uint32_t query_item = query & 0xfffu;
  if (query_group == 0xffu) return true;
  if (query_group != ((id >> 16) & 0xffu)) return false;
  return query_item == 0xfffu || query_item == (id & 0xfffu);
}

// True when `raw` (the wire value, value_size() bytes) is a value the key accepts: it fits
// the type, and lies in the documented range or is a documented enumeration constant.
bool value_valid(const CfgKey& k, std::uint64_t raw);

// Keys of `firmware` (one kFw* bit) only.
bool key_in_firmware(const CfgKey& k, std::uint8_t firmware);

}  // namespace navemu::ubx
