#pragma once
// Declarative UBX payload layouts: one compile-time description per message drives its
// encoder, its decoder (with the length check) and the generic round-trip tests.
//
// A description lists the payload as the interface description's table does, in wire order:
// each row a wire type (UBX-13003221 section 32.3.5 "Data Types": U1 I1 X1 U2 I2 X2 U4 I4 X4
// R4 R8 CH), the field's name in the table, the struct member it maps to and, where the wire
// unit is a fraction of the quantity's unit, the value of one LSB in that unit (the scale: 1e-7
// for a longitude in 1e-7 deg gives degrees, 1e-3 for a height in mm gives metres). Beside single fields a description holds
//   - the count of a repeated block (a U1 field whose value is the number of blocks; U2 in
//     MON-PATCH),
//   - one repeated block (a vector member; its rows describe one element), counted by that
//     field or following from the length (then possibly with a least number of blocks: a
//     CFG-PRT set carries at least one port, its empty form being the poll),
//   - optional groups of last fields, present or not by the length, each only after the one
//     before (CFG-PRT and CFG-TP5 polls, CFG-CFG, CFG-NMEA's 4/12/20-byte forms),
//   - configuration key/value pairs whose value size follows from the key ID (UBX-18010854
//     section 6), or the rest of the payload as text (INF messages).
// Rows that several descriptions share (a CFG-PRT port block, the datum of CFG-DAT) are written
// once as a group and used as rows wherever they occur.
// The engine is pure and allocation-free while encoding (append into a vector with capacity):
// explicit little-endian Writer/Reader calls, no packed structs. Everything about a row
// (its wire type, size and member) is a compile-time constant, so the generated code is the
// hand-written sequence of Writer calls. Each row checks at compile time that its member's C++
// type is the one of its wire type (U4 -> std::uint32_t, R8 -> double, U1 with an array
// member -> U1[n], CH[n] -> std::string).

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "protocols/ubx.hpp"

namespace navemu::ubx {

struct MsgId {
  std::uint8_t cls = 0;
  std::uint8_t id = 0;
  friend constexpr bool operator==(MsgId, MsgId) = default;
};

// Wire types (UBX-13003221 section 32.3.5). X are bit fields of the size of U; CH is one
// character of a NUL-padded string.
enum class Wire : std::uint8_t { kU1, kI1, kX1, kU2, kI2, kX2, kU4, kI4, kX4, kR4, kR8, kCh };

constexpr std::size_t wire_size(Wire w) {
  switch (w) {
    case Wire::kU2:
    case Wire::kI2:
    case Wire::kX2:
      return 2;
    case Wire::kU4:
    case Wire::kI4:
    case Wire::kX4:
    case Wire::kR4:
      return 4;
    case Wire::kR8:
      return 8;
    default:
      return 1;
  }
}

// The C++ type a member of wire type W has.
template <Wire W>
struct WireValue;
template <> struct WireValue<Wire::kU1> { using type = std::uint8_t; };
template <> struct WireValue<Wire::kX1> { using type = std::uint8_t; };
template <> struct WireValue<Wire::kI1> { using type = std::int8_t; };
template <> struct WireValue<Wire::kU2> { using type = std::uint16_t; };
template <> struct WireValue<Wire::kX2> { using type = std::uint16_t; };
template <> struct WireValue<Wire::kI2> { using type = std::int16_t; };
template <> struct WireValue<Wire::kU4> { using type = std::uint32_t; };
template <> struct WireValue<Wire::kX4> { using type = std::uint32_t; };
template <> struct WireValue<Wire::kI4> { using type = std::int32_t; };
template <> struct WireValue<Wire::kR4> { using type = float; };
template <> struct WireValue<Wire::kR8> { using type = double; };
template <Wire W>
using wire_value_t = typename WireValue<W>::type;

// How a payload's length is checked against a description without a repeated block.
enum class Length : std::uint8_t {
  kAtLeast,  // output messages: later protocol versions may append fields (section 32.3)
  kExact,    // messages whose length selects their meaning (CFG polls and sets), ACK, MON-HW
};

namespace layout {

// ---- scalar access -------------------------------------------------------------------------

template <class T>
void put_value(Writer& w, T v) {
  if constexpr (std::is_same_v<T, std::uint8_t>) w.u1(v);
  else if constexpr (std::is_same_v<T, std::int8_t>) w.i1(v);
  else if constexpr (std::is_same_v<T, std::uint16_t>) w.u2(v);
  else if constexpr (std::is_same_v<T, std::int16_t>) w.i2(v);
  else if constexpr (std::is_same_v<T, std::uint32_t>) w.u4(v);
  else if constexpr (std::is_same_v<T, std::int32_t>) w.i4(v);
  else if constexpr (std::is_same_v<T, float>) w.r4(v);
  else w.r8(v);
}

template <class T>
T get_value(const Reader& r, std::size_t off) {
  if constexpr (std::is_same_v<T, std::uint8_t>) return r.u1(off);
  else if constexpr (std::is_same_v<T, std::int8_t>) return r.i1(off);
  else if constexpr (std::is_same_v<T, std::uint16_t>) return r.u2(off);
  else if constexpr (std::is_same_v<T, std::int16_t>) return r.i2(off);
  else if constexpr (std::is_same_v<T, std::uint32_t>) return r.u4(off);
  else if constexpr (std::is_same_v<T, std::int32_t>) return r.i4(off);
  else if constexpr (std::is_same_v<T, float>) return r.r4(off);
  else return r.r8(off);
}

// A NUL-padded CH[n] field: at most n - 1 characters are sent so that a NUL ends the string;
// decoding stops at the first NUL.
inline void put_string(Writer& w, const std::string& s, std::size_t size) {
  const std::size_t n = std::min(s.size(), size - 1);
  w.bytes(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(s.data()), n));
  w.zeros(size - n);
}

inline std::string get_string(const Reader& r, std::size_t off, std::size_t size) {
  std::string s;
  for (std::size_t i = 0; i < size; ++i) {
    const std::uint8_t c = r.u1(off + i);
    if (c == 0) break;
    s.push_back(static_cast<char>(c));
  }
  return s;
}

template <class T>
struct ArrayOf : std::false_type {};
template <class T, std::size_t N>
struct ArrayOf<std::array<T, N>> : std::true_type {
  using element = T;
  static constexpr std::size_t kSize = N;
};

// One value of wire type W held in a C++ object of type V: a scalar, an array of scalars
// (U1[n]) or a string (CH[n], n = chars).
template <Wire W, class V, std::size_t Chars>
struct Value {
  using Value_t = V;
  static constexpr std::size_t size() {
    if constexpr (W == Wire::kCh) return Chars;
    else if constexpr (ArrayOf<V>::value) return ArrayOf<V>::kSize * wire_size(W);
    else return wire_size(W);
  }
  static void put(Writer& w, const V& v) {
    if constexpr (W == Wire::kCh) {
      put_string(w, v, Chars);
    } else if constexpr (ArrayOf<V>::value) {
      for (const auto& e : v) put_value(w, e);
    } else {
      put_value(w, v);
    }
  }
  static void get(const Reader& r, std::size_t off, V& v) {
    if constexpr (W == Wire::kCh) {
      v = get_string(r, off, Chars);
    } else if constexpr (ArrayOf<V>::value) {
      for (std::size_t i = 0; i < v.size(); ++i)
        v[i] = get_value<typename ArrayOf<V>::element>(r, off + i * wire_size(W));
    } else {
      v = get_value<V>(r, off);
    }
  }
  static constexpr bool type_matches() {
    if constexpr (W == Wire::kCh) return std::is_same_v<V, std::string> && Chars > 0;
    else if constexpr (ArrayOf<V>::value)
      return std::is_same_v<typename ArrayOf<V>::element, wire_value_t<W>>;
    else return std::is_same_v<V, wire_value_t<W>>;
  }
  static_assert(type_matches(), "the member's C++ type is not the one of its wire type");
};

// ---- lists of rows and of descriptions ----------------------------------------------------

// A fixed list of values, of equal types or not: the rows of a description, block or group,
// and the table of descriptions. An aggregate with one base per value instead of a std::tuple,
// whose constructors and recursive bases cost each translation unit that includes the hundred
// descriptions of ubx_messages.hpp about 24 s of compile time and 1.7 GB (g++ 12).
template <std::size_t I, class T>
struct Slot {
  T value;
};
template <class Seq, class... T>
struct ListOf;
template <std::size_t... I, class... T>
struct ListOf<std::index_sequence<I...>, T...> : Slot<I, T>... {
  // fn(values...), in list order.
  template <class Fn>
  constexpr decltype(auto) apply(Fn&& fn) const {
    return fn(static_cast<const Slot<I, T>&>(*this).value...);
  }
};
template <class... T>
using List = ListOf<std::index_sequence_for<T...>, T...>;
template <class... T>
constexpr List<T...> list(T... values) {
  return {{values}...};
}

// ---- rows of a description -----------------------------------------------------------------

// Decoding state shared by the rows of one payload: the block count read from its field.
struct Cursor {
  std::size_t off = 0;
  std::size_t blocks = 0;
};

// A field mapped to member `member` of S. Values outside [lo, hi] (when `checked`) fail to
// decode (e.g. the version byte that tells CFG-VALGET's request from its answer).
template <Wire W, class S, class M, std::size_t Chars = 0>
struct Field {
  using Struct = S;
  using V = Value<W, M, Chars>;
  static constexpr Wire kWire = W;
  static constexpr std::size_t kSize = V::size();
  M S::*member;
  const char* name;
  double scale = 1.0;
  bool checked = false;
  std::int64_t lo = 0, hi = 0;

  // The same field, accepted on decoding only within [min, max].
  constexpr Field only(std::int64_t min, std::int64_t max) const {
    Field f = *this;
    f.checked = true;
    f.lo = min;
    f.hi = max;
    return f;
  }
  void put(Writer& w, const S& m, std::size_t) const { V::put(w, m.*member); }
  bool get(const Reader& r, Cursor& c, S& m) const {
    V::get(r, c.off, m.*member);
    c.off += kSize;
    if constexpr (std::is_integral_v<M>) {
      if (checked && (static_cast<std::int64_t>(m.*member) < lo ||
                      static_cast<std::int64_t>(m.*member) > hi))
        return false;
    }
    return true;
  }
};

// The number of repeated blocks that follow (U1, or U2: at most 255 or 65535 are sent).
template <Wire W>
struct Count {
  static_assert(W == Wire::kU1 || W == Wire::kU2);
  static constexpr Wire kWire = W;
  static constexpr std::size_t kSize = wire_size(W);
  static constexpr std::size_t kMax = W == Wire::kU1 ? 0xFF : 0xFFFF;
  const char* name;
  template <class S>
  void put(Writer& w, const S&, std::size_t blocks) const {
    if constexpr (W == Wire::kU1) w.u1(static_cast<std::uint8_t>(blocks));
    else w.u2(static_cast<std::uint16_t>(blocks));
  }
  template <class S>
  bool get(const Reader& r, Cursor& c, S&) const {
    c.blocks = W == Wire::kU1 ? r.u1(c.off) : r.u2(c.off);
    c.off += kSize;
    return true;
  }
};

// A group of last fields that is present or not (the payload is kOptionalSize longer when it
// is). Several groups follow one another, each present only with the ones before it; a
// decoded absent group leaves its members at their defaults.
template <class S, class... Rows>
struct Optional {
  using Struct = S;
  static constexpr std::size_t kSize = 0;  // not part of the fixed length
  static constexpr std::size_t kOptionalSize = (Rows::kSize + ...);
  bool S::*present;
  List<Rows...> rows;
  void put(Writer& w, const S& m, std::size_t) const {
    if (m.*present) rows.apply([&](const auto&... row) { (row.put(w, m, 0), ...); });
  }
  bool get(const Reader& r, Cursor& c, S& m) const {
    m.*present = r.size() >= c.off + kOptionalSize;
    bool ok = true;
    rows.apply([&](const auto&... row) {
      if (m.*present) ((ok = row.get(r, c, m) && ok), ...);
      else ((m.*row.member = {}), ...);
    });
    return ok;
  }
};

// The rest of the payload as text, every byte kept (INF messages: "CH[N]", N from the length).
template <class S>
struct Text {
  using Struct = S;
  static constexpr std::size_t kSize = 0;
  std::string S::*member;
  const char* name;
  void put(Writer& w, const S& m, std::size_t) const {
    const std::string& t = m.*member;
    w.bytes(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(t.data()), t.size()));
  }
  bool get(const Reader& r, Cursor& c, S& m) const {
    std::string& t = m.*member;
    t.clear();
    for (; c.off < r.size(); ++c.off) t.push_back(static_cast<char>(r.u1(c.off)));
    return true;
  }
};

// The element itself as the row of a block of scalars or strings (RXM-SFRBX words, CFG-VALGET
// keys, MON-VER extensions).
template <Wire W, class E, std::size_t Chars = 0>
struct Self {
  using V = Value<W, E, Chars>;
  static constexpr std::size_t kSize = V::size();
  const char* name;
  void put(Writer& w, const E& e, std::size_t) const { V::put(w, e); }
  bool get(const Reader& r, Cursor& c, E& e) const {
    V::get(r, c.off, e);
    c.off += kSize;
    return true;
  }
};

// How many blocks an encoder sends at most: the count field's range, or as many as the 16-bit
// length takes (MON-VER), or all (CFG-VALGET keys: at most 64 by specification, not
// truncated; a frame over the length is not sent).
enum class Repeat : std::uint8_t { kCounted, kFitLength, kAll };

template <class S, class E, Repeat R, class... Rows>
struct Block {
  using Struct = S;
  static constexpr std::size_t kSize = 0;
  static constexpr std::size_t kBlockSize = (Rows::kSize + ...);
  static constexpr Repeat kRepeat = R;
  std::vector<E> S::*member;
  List<Rows...> rows;
  std::size_t min_blocks = 0;  // fewer blocks fail to decode

  // The same block, decoded only when at least n blocks are present.
  constexpr Block at_least(std::size_t n) const {
    Block b = *this;
    b.min_blocks = n;
    return b;
  }
  void put(Writer& w, const S& m, std::size_t blocks) const {
    const std::vector<E>& v = m.*member;
    for (std::size_t i = 0; i < blocks; ++i)
      rows.apply([&](const auto&... row) { (row.put(w, v[i], 0), ...); });
  }
  bool get(const Reader& r, Cursor& c, S& m) const {
    std::vector<E>& v = m.*member;
    v.resize(c.blocks);
    bool ok = true;
    for (std::size_t i = 0; i < c.blocks; ++i)
      rows.apply([&](const auto&... row) { ((ok = row.get(r, c, v[i]) && ok), ...); });
    return ok;
  }
};

// CFG-VALGET answer / CFG-VALSET pairs: key ID (U4), then cfg_value_size(key) bytes of value
// (UBX-18010854 section 6); a reserved size code or a truncated value fails.
template <class S, class KV>
struct KeyValues {
  using Struct = S;
  static constexpr std::size_t kSize = 0;
  std::vector<KV> S::*member;
  std::size_t (*value_size)(std::uint32_t key_id);
  void put(Writer& w, const S& m, std::size_t) const {
    for (const KV& kv : m.*member) {
      w.u4(kv.key_id);
      const std::size_t n = value_size(kv.key_id);
      for (std::size_t i = 0; i < n; ++i)
        w.u1(static_cast<std::uint8_t>((kv.value >> (8 * i)) & 0xFF));
    }
  }
  bool get(const Reader& r, Cursor& c, S& m) const {
    std::vector<KV>& v = m.*member;
    v.clear();
    while (c.off < r.size()) {
      if (r.size() - c.off < 4) return false;
      KV kv;
      kv.key_id = r.u4(c.off);
      c.off += 4;
      const std::size_t n = value_size(kv.key_id);
      if (n == 0 || r.size() - c.off < n) return false;
      for (std::size_t i = 0; i < n; ++i)
        kv.value |= static_cast<std::uint64_t>(r.u1(c.off + i)) << (8 * i);
      c.off += n;
      v.push_back(kv);
    }
    return true;
  }
};

template <class T>
struct IsBlock : std::false_type {};
template <class S, class E, Repeat R, class... Rows>
struct IsBlock<Block<S, E, R, Rows...>> : std::true_type {};
template <class T>
struct IsOptional : std::false_type {};
template <class S, class... Rows>
struct IsOptional<Optional<S, Rows...>> : std::true_type {};
template <class T>
struct IsCount : std::false_type {};
template <Wire W>
struct IsCount<Count<W>> : std::true_type {};
// Rows that take the rest of the payload, whatever its length.
template <class T>
struct IsRest : std::false_type {};
template <class S, class KV>
struct IsRest<KeyValues<S, KV>> : std::true_type {};
template <class S>
struct IsRest<Text<S>> : std::true_type {};
template <class T>
struct IsKeyValues : std::false_type {};
template <class S, class KV>
struct IsKeyValues<KeyValues<S, KV>> : std::true_type {};

// True for rows holding NUL-padded text (CH), whose bytes after the NUL a decoder drops.
template <class Row>
constexpr bool has_text() {
  if constexpr (IsBlock<Row>::value)
    return []<class Seq, class... R>(ListOf<Seq, R...>*) { return (has_text<R>() || ...); }(
        static_cast<decltype(Row::rows)*>(nullptr));
  else if constexpr (requires { Row::V::size(); }) return std::is_same_v<typename Row::V::Value_t, std::string>;
  else return false;
}

template <class Row>
constexpr std::size_t block_size_of() {
  if constexpr (IsBlock<Row>::value) return Row::kBlockSize;
  else return 0;
}
template <class Row>
constexpr Repeat repeat_of(Repeat r) {
  if constexpr (IsBlock<Row>::value) return Row::kRepeat;
  else return r;
}
template <class Row>
constexpr std::size_t optional_size_of() {
  if constexpr (IsOptional<Row>::value) return Row::kOptionalSize;
  else return 0;
}
template <class Row>
constexpr std::size_t count_size_of() {
  if constexpr (IsCount<Row>::value) return Row::kSize;
  else return 0;
}

// A description's rows written as single rows or as groups (lists of rows) of them, in wire
// order, as one list of rows.
template <class T>
struct IsGroup : std::false_type {};
template <class Seq, class... R>
struct IsGroup<ListOf<Seq, R...>> : std::true_type {};
template <class R>
constexpr auto as_group(const R& r) {
  if constexpr (IsGroup<R>::value) return r;
  else return list(r);
}
template <class A, class B>
constexpr auto concat(const A& a, const B& b) {
  return a.apply([&](const auto&... x) { return b.apply([&](const auto&... y) { return list(x..., y...); }); });
}
template <class... R>
constexpr auto flatten(const R&... rows) {
  return list(rows...);
}
template <class First, class... Rest>
  requires(IsGroup<First>::value || (IsGroup<Rest>::value || ...))
constexpr auto flatten(const First& first, const Rest&... rest) {
  return concat(as_group(first), flatten(rest...));
}

}  // namespace layout

// ---- a message's description ---------------------------------------------------------------

template <class S, class... Rows>
struct Layout {
  using Struct = S;
  MsgId id;
  const char* name;  // as u-blox writes it: "NAV-PVT"
  Length length;
  layout::List<Rows...> rows;

  // Bytes before the repeated part (the whole payload when there is none).
  static constexpr std::size_t kHeaderSize = (std::size_t{0} + ... + Rows::kSize);
  static constexpr bool kHasBlock = (false || ... || layout::IsBlock<Rows>::value);
  static constexpr bool kHasOptional = (false || ... || layout::IsOptional<Rows>::value);
  static constexpr bool kHasRest = (false || ... || layout::IsRest<Rows>::value);
  static constexpr bool kHasKeyValues = (false || ... || layout::IsKeyValues<Rows>::value);
  static constexpr bool kHasText = (false || ... || layout::has_text<Rows>());
  // Size of one repeated block (0: none).
  static constexpr std::size_t kBlockSize = [] {
    std::size_t n = 0;
    ((n += layout::block_size_of<Rows>()), ...);
    return n;
  }();
  static constexpr layout::Repeat kRepeat = [] {
    layout::Repeat r = layout::Repeat::kAll;
    ((r = layout::repeat_of<Rows>(r)), ...);
    return r;
  }();
  // Offset of the count field (kHeaderSize: none) and its size (1 or 2 bytes).
  static constexpr std::size_t kCountOffset = [] {
    std::size_t off = 0;
    bool found = false;
    ((found = found || layout::IsCount<Rows>::value, off += found ? 0 : Rows::kSize), ...);
    return found ? off : kHeaderSize;
  }();
  static constexpr std::size_t kCountSize = (std::size_t{0} + ... + layout::count_size_of<Rows>());
  static constexpr bool kCounted = kCountOffset < kHeaderSize;
  static constexpr std::size_t kCountMax = kCountSize == 1 ? 0xFF : 0xFFFF;
  // Bytes of all optional groups (0: none).
  static constexpr std::size_t kOptionalSize = (std::size_t{0} + ... + layout::optional_size_of<Rows>());
  static_assert(!kCounted || (kHasBlock && kRepeat == layout::Repeat::kCounted),
                "a count field needs a counted block");

  // The length check of a payload before it is decoded.
  constexpr bool fits(std::span<const std::uint8_t> p) const {
    if (p.size() < kHeaderSize) return false;
    if constexpr (kCounted) {
      std::size_t n = p[kCountOffset];
      if constexpr (kCountSize == 2) n |= std::size_t{p[kCountOffset + 1]} << 8;
      return p.size() == kHeaderSize + kBlockSize * n && n >= min_blocks();
    } else if constexpr (kHasBlock) {
      const std::size_t rest = p.size() - kHeaderSize;
      return rest % kBlockSize == 0 && rest / kBlockSize >= min_blocks();
    } else if constexpr (kHasRest) {
      return true;
    } else if constexpr (kHasOptional) {
      // The fixed part, then each optional group only after the ones before it.
      bool ok = p.size() == kHeaderSize;
      std::size_t n = kHeaderSize;
      ((n += layout::optional_size_of<Rows>(), ok = ok || p.size() == n), ...);
      return ok;
    } else {
      return length == Length::kAtLeast || p.size() == kHeaderSize;
    }
  }

  // The least number of repeated blocks a payload carries (0 without a block).
  constexpr std::size_t min_blocks() const {
    std::size_t n = 0;
    rows.apply([&](const auto&... row) {
      ((n = std::max(n, layout::IsBlock<std::remove_cvref_t<decltype(row)>>::value ? min_of(row) : 0)), ...);
    });
    return n;
  }

  // Blocks an encoder sends of `m` (0 without a block).
  std::size_t blocks(const S& m) const {
    std::size_t n = 0;
    rows.apply([&](const auto&... row) { ((n += count_of(row, m)), ...); });
    return n;
  }

  void append(const S& m, std::vector<std::uint8_t>& out) const {
    const std::size_t n = blocks(m);
    const std::size_t start = begin_frame(id.cls, id.id, out);
    Writer w(out);
    rows.apply([&](const auto&... row) { (row.put(w, m, n), ...); });
    end_frame(start, out);
  }

  bool decode(std::span<const std::uint8_t> p, S& m) const {
    if (!fits(p)) return false;
    const Reader r(p);
    layout::Cursor c;
    if constexpr (kHasBlock && !kCounted) c.blocks = (p.size() - kHeaderSize) / kBlockSize;
    bool ok = true;
    rows.apply([&](const auto&... row) { ((ok = row.get(r, c, m) && ok), ...); });
    return ok && r.ok();
  }

  // Calls fn(name, wire, value) for every scalar field of the fixed part, in wire order, the
  // value in the quantity's unit (the scale applied: degrees, metres, seconds).
  template <class Fn>
  void for_each_value(const S& m, Fn&& fn) const {
    rows.apply([&](const auto&... row) { (visit(row, m, fn), ...); });
  }

 private:
  template <class Row>
  static constexpr std::size_t min_of(const Row& row) {
    if constexpr (layout::IsBlock<Row>::value) return row.min_blocks;
    else return 0;
  }
  template <class Row>
  static std::size_t count_of(const Row& row, const S& m) {
    if constexpr (layout::IsBlock<Row>::value) {
      const std::size_t n = (m.*row.member).size();
      if constexpr (Row::kRepeat == layout::Repeat::kCounted)
        return std::min(n, kCountMax);
      else if constexpr (Row::kRepeat == layout::Repeat::kFitLength)
        return std::min(n, (kMaxWirePayload - kHeaderSize) / Row::kBlockSize);
      else return n;
    } else {
      return 0;
    }
  }
  template <class Row, class Fn>
  static void visit(const Row& row, const S& m, Fn& fn) {
    if constexpr (requires(const Row& x) { x.scale; }) {
      using M = std::remove_cvref_t<decltype(m.*row.member)>;
      if constexpr (std::is_arithmetic_v<M>)
        fn(row.name, Row::kWire, static_cast<double>(m.*row.member) * row.scale);
    }
  }
};

// ---- building descriptions -----------------------------------------------------------------
// The rows a description is written with, one per wire type and named as in the tables:
// u4(&NavPvt::i_tow_ms, "iTOW", 1e-3). The table of descriptions (ubx::Descriptions) derives
// from Describing, so the names are in scope there and nowhere else.

template <Wire W>
struct FieldOf {
  template <class S, class M>
  constexpr layout::Field<W, S, M> operator()(M S::*member, const char* name,
                                              double scale = 1.0) const {
    return {member, name, scale};
  }
};

struct Describing {
  static constexpr FieldOf<Wire::kU1> u1{};
  static constexpr FieldOf<Wire::kI1> i1{};
  static constexpr FieldOf<Wire::kX1> x1{};
  static constexpr FieldOf<Wire::kU2> u2{};
  static constexpr FieldOf<Wire::kI2> i2{};
  static constexpr FieldOf<Wire::kX2> x2{};
  static constexpr FieldOf<Wire::kU4> u4{};
  static constexpr FieldOf<Wire::kI4> i4{};
  static constexpr FieldOf<Wire::kX4> x4{};
  static constexpr FieldOf<Wire::kR4> r4{};
  static constexpr FieldOf<Wire::kR8> r8{};
  using Repeat = layout::Repeat;

  // A message's description: its rows, single or in groups, in wire order.
  template <class S, class... R>
  static constexpr auto describe(MsgId id, const char* name, Length length, R... rows) {
    return layout::flatten(rows...).apply(
        [&](auto... r) { return Layout<S, decltype(r)...>{id, name, length, layout::list(r...)}; });
  }
  // Rows written once and used in several descriptions (as the rows of a message and of a
  // block of another, or by a struct and the structs derived from it).
  template <class... R>
  static constexpr layout::List<R...> group(R... rows) {
    return layout::list(rows...);
  }
  // CH[n]: a NUL-padded string of n characters.
  template <std::size_t N, class S>
  static constexpr layout::Field<Wire::kCh, S, std::string, N> ch(std::string S::*member,
                                                                  const char* name) {
    return {member, name};
  }
  // The count of the repeated block (U1; U2 where the table says so).
  static constexpr layout::Count<Wire::kU1> count(const char* name) { return {name}; }
  static constexpr layout::Count<Wire::kU2> count_u2(const char* name) { return {name}; }
  // A repeated block of E counted by the count field: block(&NavSat::svs, rows of E...).
  template <class S, class E, class... R>
  static constexpr auto block(std::vector<E> S::*member, R... rows) {
    return block_of<Repeat::kCounted>(member, rows...);
  }
  // A repeated block whose count follows from the length; an encoder sends as many as the
  // frame takes (Repeat::kFitLength) or every element (Repeat::kAll).
  template <Repeat P, class S, class E, class... R>
  static constexpr auto block_to_end(std::vector<E> S::*member, R... rows) {
    return block_of<P>(member, rows...);
  }
  // The element itself as the only row of a block: self<Wire::kU4, std::uint32_t>("dwrd").
  template <Wire W, class E, std::size_t Chars = 0>
  static constexpr layout::Self<W, E, Chars> self(const char* name) {
    return {name};
  }
  // A group of last fields, present (and `present` true) when the payload is that much
  // longer: optional(&CfgCfg::has_device_mask, x1(&CfgCfg::device_mask, "deviceMask")).
  template <class S, class... R>
  static constexpr auto optional(bool S::*present, R... rows) {
    return layout::flatten(rows...).apply(
        [&](auto... r) { return layout::Optional<S, decltype(r)...>{present, layout::list(r...)}; });
  }
  // The rest of the payload as text, byte for byte.
  template <class S>
  static constexpr layout::Text<S> text(std::string S::*member, const char* name) {
    return {member, name};
  }
  // Configuration key/value pairs to the end of the payload.
  template <class S, class KV>
  static constexpr layout::KeyValues<S, KV> key_values(std::vector<KV> S::*member,
                                                       std::size_t (*value_size)(std::uint32_t)) {
    return {member, value_size};
  }

 private:
  template <Repeat P, class S, class E, class... R>
  static constexpr auto block_of(std::vector<E> S::*member, R... rows) {
    return layout::flatten(rows...).apply(
        [&](auto... r) { return layout::Block<S, E, P, decltype(r)...>{member, layout::list(r...)}; });
  }
};

// The description of S in a table of descriptions (a layout::List): the one entry whose layout
// describes S, found by template argument deduction.
template <class S, std::size_t I, class... R>
constexpr const Layout<S, R...>& layout_in(const layout::Slot<I, Layout<S, R...>>& entry) {
  return entry.value;
}

}  // namespace navemu::ubx
