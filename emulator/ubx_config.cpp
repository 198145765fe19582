#include "emulator/ubx_config.hpp"

#include <algorithm>

namespace navemu {

namespace {

constexpr std::size_t kMaxItemsPerMessage = 64;  // VALSET, VALGET, VALDEL (UBX-18010854 5.9.25-27)
constexpr std::uint8_t kDevBbr = 0x01, kDevFlash = 0x02;  // CFG-CFG deviceMask

bool is_wildcard(std::uint32_t key_id) { return (key_id & 0xFFFF) == 0xFFFF; }
std::uint32_t group_of(std::uint32_t key_id) { return (key_id >> 16) & 0xFF; }

}  // namespace

UbxConfig::UbxConfig(std::uint8_t firmware, std::span<const std::pair<std::uint32_t, std::uint64_t>> defaults) {
  for (const ubx::CfgKey& k : ubx::config_keys())
    if (k.firmware & firmware) items_.push_back({&k, k.default_raw, k.default_raw, std::nullopt, std::nullopt});
  std::sort(items_.begin(), items_.end(), [](const Item& a, const Item& b) { return a.key->id < b.key->id; });
  for (const auto& [id, raw] : defaults)
    if (const auto i = index_of(id)) items_[*i].def = items_[*i].ram = raw;
  txn_values_.reserve(kMaxItemsPerMessage);
}

std::optional<std::size_t> UbxConfig::index_of(std::uint32_t key_id) const {
  const auto it = std::lower_bound(items_.begin(), items_.end(), key_id,
                                   [](const Item& a, std::uint32_t id) { return a.key->id < id; });
  if (it == items_.end() || it->key->id != key_id) return std::nullopt;
  return static_cast<std::size_t>(it - items_.begin());
}

std::uint64_t UbxConfig::get(std::uint32_t key_id) const {
  const auto i = index_of(key_id);
  return i ? items_[*i].ram : 0;
}

template <typename Self, typename F>
bool UbxConfig::for_each_named(Self& self, std::uint32_t key_id, F&& f) {
  if (!is_wildcard(key_id)) {
    const auto i = self.index_of(key_id);
    if (!i) return false;
    f(self.items_[*i]);
    return true;
  }
  const std::uint32_t group = group_of(key_id);
  for (auto& it : self.items_)
    if (group == 0xFF || group_of(it.key->id) == group) f(it);
  return true;
}

void UbxConfig::rebuild(Item& it) const { it.ram = it.bbr ? *it.bbr : it.flash ? *it.flash : it.def; }

bool UbxConfig::apply(std::span<const ubx::CfgKeyValue> values, std::uint8_t layers) {
  // Validity is checked only when the RAM layer is written (VALSET section).
  if (layers & ubx::kLayerMaskRam)
    for (const ubx::CfgKeyValue& kv : values)
      if (!ubx::value_valid(*items_[*index_of(kv.key_id)].key, kv.value)) return false;
  for (const ubx::CfgKeyValue& kv : values) {
    Item& it = items_[*index_of(kv.key_id)];
    if (layers & ubx::kLayerMaskRam) it.ram = kv.value;
    if (layers & ubx::kLayerMaskBbr) it.bbr = kv.value;
    if (layers & ubx::kLayerMaskFlash) it.flash = kv.value;
  }
  if (layers & ubx::kLayerMaskRam) ++generation_;
  return true;
}

bool UbxConfig::set_ram(std::span<const ubx::CfgKeyValue> values) {
  for (const ubx::CfgKeyValue& kv : values)
    if (const auto i = index_of(kv.key_id); i && !ubx::value_valid(*items_[*i].key, kv.value)) return false;
  for (const ubx::CfgKeyValue& kv : values)
    if (const auto i = index_of(kv.key_id)) items_[*i].ram = kv.value;
  ++generation_;
  return true;
}

void UbxConfig::cancel_transaction() {
  txn_ = Txn::kNone;
  txn_values_.clear();
}

bool UbxConfig::valset(const ubx::CfgValset& m) {
  if (txn_ == Txn::kDel) cancel_transaction();  // another CFG message
  const std::uint8_t action = m.version == 0 ? 0 : m.transaction;
  const std::uint8_t layers = m.layers & (ubx::kLayerMaskRam | ubx::kLayerMaskBbr | ubx::kLayerMaskFlash);
  const bool continues = action == 2 || action == 3;
  const bool unknown = std::any_of(m.values.begin(), m.values.end(),
                                   [&](const ubx::CfgKeyValue& kv) { return !index_of(kv.key_id); });
  if (layers == 0 || unknown || m.values.size() > kMaxItemsPerMessage || action > 3 || m.version > 1 ||
      (continues && (txn_ != Txn::kSet || layers != txn_layers_))) {
    cancel_transaction();
    return false;
  }
  if (action == 0) {
    cancel_transaction();
    return apply(m.values, layers);
  }
  if (action == 1) {
    cancel_transaction();
    txn_ = Txn::kSet;
    txn_layers_ = layers;
  }
  txn_values_.insert(txn_values_.end(), m.values.begin(), m.values.end());
  if (action != 3) return true;
  const bool ok = apply(txn_values_, layers);  // invalid: NAK for the applying message only
  cancel_transaction();
  return ok;
}

bool UbxConfig::valdel(const ubx::CfgValdel& m) {
  if (txn_ == Txn::kSet) cancel_transaction();
  const std::uint8_t action = m.version == 0 ? 0 : m.transaction;
  const std::uint8_t layers = m.layers & (ubx::kLayerMaskBbr | ubx::kLayerMaskFlash);
  const bool continues = action == 2 || action == 3;
  const bool unknown = std::any_of(m.keys.begin(), m.keys.end(), [&](std::uint32_t k) {
    return !is_wildcard(k) && !index_of(k);
  });
  if (layers == 0 || unknown || m.keys.size() > kMaxItemsPerMessage || action > 3 || m.version > 1 ||
      (continues && (txn_ != Txn::kDel || layers != txn_layers_))) {
    cancel_transaction();
    return false;
  }
  if (action == 0 || action == 1) cancel_transaction();
  if (action == 1) {
    txn_ = Txn::kDel;
    txn_layers_ = layers;
  }
  for (std::uint32_t k : m.keys) txn_values_.push_back({k, 0});
  if (action == 1 || action == 2) return true;
  for (const ubx::CfgKeyValue& kv : txn_values_)
    for_each_named(*this, kv.key_id, [&](Item& it) {
      if (layers & ubx::kLayerMaskBbr) it.bbr.reset();
      if (layers & ubx::kLayerMaskFlash) it.flash.reset();
    });
  cancel_transaction();
  return true;
}

std::optional<ubx::CfgValgetResponse> UbxConfig::valget(const ubx::CfgValgetRequest& m) const {
  if (m.keys.size() > kMaxItemsPerMessage ||
      (m.layer != ubx::kLayerRam && m.layer != ubx::kLayerBbr && m.layer != ubx::kLayerFlash &&
       m.layer != ubx::kLayerDefault))
    return std::nullopt;
  ubx::CfgValgetResponse r;
  r.layer = m.layer;
  r.position = m.position;
  std::size_t skip = m.position;
  bool known = true;
  for (std::uint32_t k : m.keys) {
    known = known && for_each_named(*this, k, [&](const Item& it) {
      const std::optional<std::uint64_t> v = m.layer == ubx::kLayerRam   ? std::optional(it.ram)
                                             : m.layer == ubx::kLayerBbr ? it.bbr
                                             : m.layer == ubx::kLayerFlash ? it.flash
                                                                           : std::optional(it.def);
      if (!v) return;
      if (skip > 0) {
        --skip;
        return;
      }
      if (r.values.size() < kMaxItemsPerMessage) r.values.push_back({it.key->id, *v});
    });
  }
  if (!known || r.values.empty()) return std::nullopt;
  return r;
}

void UbxConfig::clear(std::uint8_t device_mask) {
  for (Item& it : items_) {
    if (device_mask & kDevBbr) it.bbr.reset();
    if (device_mask & kDevFlash) it.flash.reset();
  }
}

// Each layer keeps what differs from the layers below it, so that a load gives RAM back.
void UbxConfig::save(std::uint8_t device_mask) {
  for (Item& it : items_) {
    if (device_mask & kDevFlash) it.flash = it.ram != it.def ? std::optional(it.ram) : std::nullopt;
    if (device_mask & kDevBbr)
      it.bbr = it.ram != (it.flash ? *it.flash : it.def) ? std::optional(it.ram) : std::nullopt;
  }
}

void UbxConfig::load() {
  for (Item& it : items_) rebuild(it);
  ++generation_;
}

}  // namespace navemu
