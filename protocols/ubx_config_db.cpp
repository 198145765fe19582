#include "protocols/ubx_config_db.hpp"

#include <array>
#include <bit>
#include <utility>

namespace navemu::ubx {
namespace {

constexpr CfgRange kAnyValue{CfgRangeKind::kAny, 0.0, 0.0, 0};

constexpr CfgRange range_of(double min, double max) {
  return CfgRange{CfgRangeKind::kMinMax, min, max, 0};
}

constexpr CfgRange enum_of(std::initializer_list<unsigned> values) {
  std::uint64_t mask = 0;
  for (unsigned v : values) mask |= std::uint64_t{1} << v;
  return CfgRange{CfgRangeKind::kEnum, 0.0, 0.0, mask};
}

constexpr CfgDefaultSource kF9pDocument = CfgDefaultSource::kF9pDocument;
constexpr CfgDefaultSource kGen9Sibling = CfgDefaultSource::kGen9Sibling;
constexpr CfgDefaultSource kUnestablished = CfgDefaultSource::kUnestablished;

constexpr CfgKey kKeys[] = {
#include "protocols/ubx_config_db_table.inc"
};

// Groups in the order of the table; the group byte is read from the first key of each.
constexpr auto make_groups() {
  constexpr std::size_t kMaxGroups = 64;
  std::array<CfgGroup, kMaxGroups> groups{};
  std::size_t n = 0;
  for (const CfgKey& k : kKeys) {
    const auto gid = static_cast<std::uint8_t>((k.id >> 16) & 0xffu);
    bool seen = false;
    for (std::size_t i = 0; i < n; ++i) seen = seen || groups[i].group_id == gid;
    if (seen) continue;
    const std::string_view rest = k.name.substr(4);  // after "CFG-"
    groups[n++] = CfgGroup{k.name.substr(0, 4 + rest.find('-')), gid};
  }
  return std::pair{groups, n};
}
constexpr auto kGroupTable = make_groups();

bool is_signed(CfgType t) {
  return t == CfgType::kI1 || t == CfgType::kI2 || t == CfgType::kI4 || t == CfgType::kI8;
}

// The wire value as a number, for range checks.
double numeric_value(CfgType type, std::size_t size, std::uint64_t raw) {
  if (type == CfgType::kR4) {
    return static_cast<double>(std::bit_cast<float>(static_cast<std::uint32_t>(raw)));
  }
  if (type == CfgType::kR8) return std::bit_cast<double>(raw);
  if (is_signed(type)) {
    const unsigned shift = static_cast<unsigned>(64 - 8 * size);
    return static_cast<double>(static_cast<std::int64_t>(raw << shift) >> shift);
  }
  return static_cast<double>(raw);
}

}  // namespace

std::span<const CfgKey> config_keys() { return kKeys; }

std::span<const CfgGroup> config_groups() {
  return std::span<const CfgGroup>(kGroupTable.first.data(), kGroupTable.second);
}

const CfgKey* find_config_key(std::uint32_t id) {
  for (const CfgKey& k : kKeys) {
    if (k.id == id) return &k;
  }
  return nullptr;
}

const CfgKey* find_config_key(std::string_view name) {
  for (const CfgKey& k : kKeys) {
    if (k.name == name) return &k;
  }
  return nullptr;
}

const CfgGroup* find_config_group(std::string_view name) {
  for (const CfgGroup& g : config_groups()) {
    if (g.name == name) return &g;
  }
  return nullptr;
}

std::size_t value_size(std::uint32_t id) {
  switch ((id >> 28) & 0x7u) {
    case 1: return 1;  // one bit, stored in one byte
    case 2: return 1;
    case 3: return 2;
    case 4: return 4;
    case 5: return 8;
    default: return 0;
  }
}

bool value_valid(const CfgKey& k, std::uint64_t raw) {
  const std::size_t size = value_size(k.id);
  if (size == 0) return false;
  if (size < 8 && (raw >> (8 * size)) != 0) return false;  // does not fit the type
  if (k.type == CfgType::kL) return raw <= 1;
  const double value = numeric_value(k.type, size, raw);  // NaN fails every kMinMax range
  switch (k.range.kind) {
    case CfgRangeKind::kAny: return true;
    case CfgRangeKind::kMinMax: return value >= k.range.min && value <= k.range.max;
    case CfgRangeKind::kEnum: return raw < 64 && ((k.range.allowed_mask >> raw) & 1u) != 0;
  }
  return false;
}

bool key_in_firmware(const CfgKey& k, std::uint8_t firmware) {
  return (k.firmware & firmware) != 0;
}

}  // namespace navemu::ubx
