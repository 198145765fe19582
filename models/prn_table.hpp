#pragma once
// Per-satellite state keyed by PRN that allocates only when built: one slot per PRN 1..99
// (RINEX satellite numbers have two digits, RINEX 3.04 sect. 3.5), each empty until first
// used. The real-time loop's satellites rise and set without touching the heap.

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace navemu {

inline constexpr int kMaxPrn = 99;

template <class T>
class PrnTable {
 public:
  PrnTable() : slots_(kMaxPrn + 1) {}

  T* find(int prn) { return valid(prn) && slots_[idx(prn)] ? &*slots_[idx(prn)] : nullptr; }
  const T* find(int prn) const {
    return valid(prn) && slots_[idx(prn)] ? &*slots_[idx(prn)] : nullptr;
  }
  // The entry of `prn`, constructed from `args` when absent; second: whether it was.
  template <class... Args>
  std::pair<T&, bool> try_emplace(int prn, Args&&... args) {
    std::optional<T>& s = slot(prn);
    const bool fresh = !s;
    if (fresh) s.emplace(std::forward<Args>(args)...);
    return {*s, fresh};
  }
  void erase(int prn) {
    if (valid(prn)) slots_[idx(prn)].reset();
  }
  void clear() {
    for (std::optional<T>& s : slots_) s.reset();
  }

 private:
  static bool valid(int prn) { return prn >= 1 && prn <= kMaxPrn; }
  static std::size_t idx(int prn) { return static_cast<std::size_t>(prn); }
  std::optional<T>& slot(int prn) {
    if (!valid(prn))
      throw std::out_of_range("PRN " + std::to_string(prn) + " outside 1.." + std::to_string(kMaxPrn));
    return slots_[idx(prn)];
  }
  std::vector<std::optional<T>> slots_;
};

}  // namespace navemu
