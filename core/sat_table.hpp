#pragma once
// Per-satellite state that allocates only when built: one slot for every satellite number each
// system defines (kGnssSystems, core/satellite.hpp), each empty until first used, so that
// satellites rise and set in the real-time loop without touching the heap.

#include <array>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/satellite.hpp"

namespace navemu {

namespace sat_table_detail {
// Where each system's slots start, in system order, and how many there are in all.
constexpr std::array<std::size_t, kGnssSystemCount + 1> slot_starts() {
  std::array<std::size_t, kGnssSystemCount + 1> s{};
  for (std::size_t i = 0; i < kGnssSystemCount; ++i)
    s[i + 1] = s[i] + static_cast<std::size_t>(kGnssSystems[i].last_number -
                                               kGnssSystems[i].first_number + 1);
  return s;
}
inline constexpr std::array<std::size_t, kGnssSystemCount + 1> kSlotStarts = slot_starts();
}  // namespace sat_table_detail

// Satellites every system defines, in SatId order.
inline constexpr std::size_t kDefinedSatellites = sat_table_detail::kSlotStarts.back();

template <class T>
class SatTable {
 public:
  SatTable() : slots_(kDefinedSatellites) {}

  T* find(SatId s) { return s.defined() && slots_[idx(s)] ? &*slots_[idx(s)] : nullptr; }
  const T* find(SatId s) const {
    return s.defined() && slots_[idx(s)] ? &*slots_[idx(s)] : nullptr;
  }
  // The entry of `s`, constructed from `args` when absent; second: whether it was. Throws
  // std::out_of_range for a number the system does not define.
  template <class... Args>
  std::pair<T&, bool> try_emplace(SatId s, Args&&... args) {
    std::optional<T>& slot = slot_of(s);
    const bool fresh = !slot;
    if (fresh) slot.emplace(std::forward<Args>(args)...);
    return {*slot, fresh};
  }
  void erase(SatId s) {
    if (s.defined()) slots_[idx(s)].reset();
  }
  void clear() {
    for (std::optional<T>& s : slots_) s.reset();
  }
  // Calls f(SatId, T&) for every entry, in SatId order.
  template <class F>
  void for_each(F&& f) {
    for_each_of(*this, f);
  }
  template <class F>
  void for_each(F&& f) const {
    for_each_of(*this, f);
  }

 private:
  template <class Self, class F>
  static void for_each_of(Self& self, F& f) {
    for (std::size_t sys = 0; sys < kGnssSystemCount; ++sys) {
      const GnssSystemInfo& info = kGnssSystems[sys];
      for (int n = info.first_number; n <= info.last_number; ++n) {
        auto& slot = self.slots_[sat_table_detail::kSlotStarts[sys] + static_cast<std::size_t>(n - info.first_number)];
        if (slot) f(SatId(info.system, n), *slot);
      }
    }
  }
  static std::size_t idx(SatId s) {
    return sat_table_detail::kSlotStarts[static_cast<std::size_t>(s.system())] +
           static_cast<std::size_t>(s.number() - s.info().first_number);
  }
  std::optional<T>& slot_of(SatId s) {
    if (!s.defined())
      throw std::out_of_range("satellite " + s.rinex() + " outside the numbers " + s.info().name +
                              " defines (" + std::to_string(s.info().first_number) + "-" +
                              std::to_string(s.info().last_number) + ")");
    return slots_[idx(s)];
  }
  std::vector<std::optional<T>> slots_;
};

}  // namespace navemu
