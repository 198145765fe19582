#pragma once
// A u-blox receiver's configuration database in its layers (ZED-F9P interface description
// UBX-18010854, chapter 6 "CFG interface", and the UBX-CFG-VALSET/VALGET/VALDEL/CFG/RST
// sections): every configuration item of the part (protocols/ubx_config_db.hpp) has a value in
// the Default layer (the part's, with the profile's own defaults over it), may have one in the
// Flash and the BBR layer, and has one in the RAM layer, the running configuration. The RAM
// layer is rebuilt from Default <- Flash <- BBR when the processor comes out of reset (section
// 6.6: CFG-RST reset modes 0x00, 0x01, 0x04) and by CFG-CFG's load.
//
// Messages the interface description defines are answered here the way it says:
//   VALSET  version 0: applied at once; version 1: in transactions (0 none, 1 (re)start,
//           2 ongoing, 3 apply and end). NAK, transaction cancelled and nothing applied: a key
//           unknown to the part, an invalid transition, the layers changing within a
//           transaction, no layer. NAK and nothing applied: a value outside its range when the
//           RAM layer is written (only then is validity checked). A key given twice: the last
//           value counts. At most 64 items per message.
//   VALGET  keys or group wildcards (item ID 0xffff: every item of the group; group 0xff
//           too: every item), from one layer (0 RAM, 1 BBR, 2 Flash, 7 Default), skipping
//           `position` items, at most 64 items per answer. NAK: a key unknown to the part, more
//           than 64 keys asked, or nothing to answer.
//   VALDEL  deletes keys (or groups) from BBR and/or Flash, with the same transactions; a key
//           not set there is no error.
//   Any other CFG message cancels a started transaction.
//   CFG-CFG clear (delete the Flash/BBR layers), save (RAM -> Flash/BBR) and load (rebuild RAM).

#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "protocols/ubx_config_db.hpp"
#include "protocols/ubx_messages.hpp"

namespace navemu {

class UbxConfig {
 public:
  // The items of firmware `firmware` (ubx::kFw* bits), with `defaults` (key ID, raw value)
  // replacing the part's defaults (a profile's firmware or product variant). Keys not in the
  // database are ignored there (the profile loader checks them).
  UbxConfig(std::uint8_t firmware, std::span<const std::pair<std::uint32_t, std::uint64_t>> defaults);

  // Whether the part has the item, and its running (RAM) value.
  bool has(std::uint32_t key_id) const { return index_of(key_id).has_value(); }
  std::uint64_t get(std::uint32_t key_id) const;  // 0 for an item the part does not have
  // Every change of the RAM layer bumps it, so that derived settings can be refreshed.
  std::uint64_t generation() const { return generation_; }

  // Sets RAM values the part changes itself or through legacy messages (CFG-PRT, CFG-MSG,
  // PUBX,40/41 ...): keys it does not have are skipped. Returns false if a value is invalid
  // (then nothing is set).
  bool set_ram(std::span<const ubx::CfgKeyValue> values);

  bool valset(const ubx::CfgValset& m);
  // The answer to a VALGET, or none for a NAK.
  std::optional<ubx::CfgValgetResponse> valget(const ubx::CfgValgetRequest& m) const;
  bool valdel(const ubx::CfgValdel& m);
  void cancel_transaction();  // any other CFG message

  // CFG-CFG on the layers of `device_mask` (bit 0 BBR, bit 1 Flash): delete them, save RAM into
  // them, rebuild RAM from the layers.
  void clear(std::uint8_t device_mask);
  void save(std::uint8_t device_mask);
  void load();
  // Reset: the RAM layer rebuilt from the layers below.
  void reload() { load(); }

 private:
  struct Item {
    const ubx::CfgKey* key;
    std::uint64_t def, ram;
    std::optional<std::uint64_t> bbr, flash;
  };
  std::optional<std::size_t> index_of(std::uint32_t key_id) const;
  // The items a key or wildcard names (wildcards: item ID 0xffff), in ID order.
  template <typename Self, typename F>
  static bool for_each_named(Self& self, std::uint32_t key_id, F&& f);
  bool apply(std::span<const ubx::CfgKeyValue> values, std::uint8_t layers);
  void rebuild(Item& it) const;

  std::vector<Item> items_;  // by key ID
  std::uint64_t generation_ = 0;
  // A started VALSET/VALDEL transaction: its kind, layers and what it collected.
  enum class Txn { kNone, kSet, kDel };
  Txn txn_ = Txn::kNone;
  std::uint8_t txn_layers_ = 0;
  std::vector<ubx::CfgKeyValue> txn_values_;
};

}  // namespace navemu
