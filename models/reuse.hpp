#pragma once
// Objects refilled every epoch without allocating: reset to their defaults while a vector
// member keeps its storage, so once grown to the largest epoch it never allocates again.

#include <utility>
#include <vector>

namespace navemu {

// Sets `obj` to T{} except `obj.*field`, which is emptied but keeps its capacity.
template <class T, class V>
T& reset_keeping_storage(T& obj, std::vector<V> T::*field) {
  std::vector<V> kept = std::move(obj.*field);
  kept.clear();
  obj = T{};
  obj.*field = std::move(kept);
  return obj;
}

}  // namespace navemu
