// The registry of described UBX messages and what is not a payload layout (polls, the
// PROTVER extension). The encoders and decoders are generated from the descriptions in
// protocols/ubx_messages.hpp by protocols/ubx_layout.hpp.
#include "protocols/ubx_messages.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <type_traits>

namespace navemu::ubx {
namespace {

template <Described T>
bool reencode(std::span<const std::uint8_t> payload, std::vector<std::uint8_t>& out) {
  T m{};
  if (!decode(payload, m)) return false;
  append(m, out);
  return true;
}

// The description agrees with the sizes the struct states (the payload tables' lengths).
template <Described T>
constexpr bool sizes_agree() {
  using L = std::remove_cvref_t<decltype(layout_of<T>)>;
  bool ok = true;
  if constexpr (requires { T::kPayloadSize; }) ok = ok && L::kHeaderSize == T::kPayloadSize;
  if constexpr (requires { T::kHeaderSize; }) ok = ok && L::kHeaderSize == T::kHeaderSize;
  if constexpr (requires { T::kBlockSize; }) ok = ok && L::kBlockSize == T::kBlockSize;
  return ok;
}

template <class L>
constexpr MessageInfo info(const L& l) {
  using T = typename L::Struct;
  static_assert(sizes_agree<T>(), "a description's length differs from its struct's");
  return {l.id,          l.name,           l.length,     L::kHeaderSize, L::kBlockSize,
          L::kCountOffset, L::kCountSize,   l.min_blocks(), L::kOptionalSize, L::kHasKeyValues,
          L::kHasText,     &reencode<T>};
}

// Every description, in the order of the tables.
constexpr auto kAll = Descriptions::kAll.apply(
    [](const auto&... l) { return std::array<MessageInfo, sizeof...(l)>{info(l)...}; });

}  // namespace

std::span<const MessageInfo> messages() { return kAll; }

const MessageInfo* find_message(MsgId id) {
  const auto it = std::find_if(kAll.begin(), kAll.end(),
                               [&](const MessageInfo& m) { return m.id == id; });
  return it == kAll.end() ? nullptr : &*it;
}

const MessageInfo* find_message(std::string_view name) {
  const auto it = std::find_if(kAll.begin(), kAll.end(),
                               [&](const MessageInfo& m) { return name == m.name; });
  return it == kAll.end() ? nullptr : &*it;
}

void append_poll(MsgId msg, std::vector<std::uint8_t>& out) {
  append_frame(msg.cls, msg.id, {}, out);
}

int protocol_version_x100(const MonVer& m) {
  for (const std::string& e : m.extensions) {
    if (e.rfind("PROTVER", 0) != 0 || e.size() < 9 || (e[7] != '=' && e[7] != ' ')) continue;
    // "PROTVER=xx.yy": integer part, optional fraction of up to two digits.
    const char* first = e.data() + 8;
    const char* last = e.data() + e.size();
    int major = 0;
    auto [p, ec] = std::from_chars(first, last, major);
    if (ec != std::errc() || major < 0) return 0;
    int minor = 0;
    if (p != last && *p == '.') {
      ++p;
      int digits = 0;
      while (p != last && *p >= '0' && *p <= '9' && digits < 2) {
        minor = minor * 10 + (*p - '0');
        ++p;
        ++digits;
      }
      if (digits == 1) minor *= 10;
    }
    return major * 100 + minor;
  }
  return 0;
}

namespace {
// n in [0, 15] nearest to sigma / scale on a log2 scale (zero or below: 0; infinite or not a
// number: 15, the worst, as cpStdev's "invalid").
std::uint8_t log2_index(double sigma, double scale) {
  if (!std::isfinite(sigma) && !(sigma < 0.0)) return 15;
  if (!(sigma > 0.0)) return 0;
  return static_cast<std::uint8_t>(std::clamp(std::lround(std::log2(sigma / scale)), 0L, 15L));
}
}  // namespace

std::uint8_t rawx_pr_stdev(double sigma_m) { return log2_index(sigma_m, 0.01); }
std::uint8_t rawx_do_stdev(double sigma_hz) { return log2_index(sigma_hz, 0.002); }
std::uint8_t rawx_cp_stdev(double sigma_cycles) {
  if (!(sigma_cycles >= 0.0)) return 15;
  return static_cast<std::uint8_t>(std::clamp(std::lround(std::min(sigma_cycles, 1.0) / 0.004), 1L, 15L));
}

}  // namespace navemu::ubx
