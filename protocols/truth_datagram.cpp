// The truth datagram codec; layout and keys in truth_datagram.hpp and docs/truth-protocol.md.
#include "protocols/truth_datagram.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <exception>
#include <iterator>
#include <optional>
#include <string_view>

namespace navemu::truth_datagram {

namespace {

constexpr std::array<std::uint8_t, 4> kMagic{'N', 'V', 'T', 'R'};
constexpr std::size_t kCrcOffset = kBinarySize - 4;
constexpr std::size_t kMaxJson = 4096;

// Flag bits of the binary header (offset 6).
constexpr std::uint16_t kFlagHostUtc = 1u << 0;
constexpr std::uint16_t kFlagPositionEcef = 1u << 1;
constexpr std::uint16_t kFlagVelocityEcef = 1u << 2;
constexpr std::uint16_t kFlagRollPitchYaw = 1u << 3;
constexpr std::uint16_t kFlagRates = 1u << 4;
constexpr std::uint16_t kFlagTemperature = 1u << 5;
constexpr std::uint16_t kFlagsDefined = 0x3F;

// Field offsets of the binary layout.
constexpr std::size_t kOffVersion = 4, kOffReserved = 5, kOffFlags = 6, kOffSequence = 8,
                      kOffTime = 12, kOffPosition = 20, kOffVelocity = 44, kOffAttitude = 68,
                      kOffForce = 100, kOffRate = 124, kOffTemperature = 148;

// ---- little-endian put/get ---------------------------------------------------------------

template <typename U>
void put_le(std::span<std::uint8_t> b, std::size_t off, U v) {
  for (std::size_t i = 0; i < sizeof(U); ++i) b[off + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

template <typename U>
U get_le(std::span<const std::uint8_t> b, std::size_t off) {
  U v = 0;
  for (std::size_t i = 0; i < sizeof(U); ++i) v = static_cast<U>(v | (U{b[off + i]} << (8 * i)));
  return v;
}

void put_f64(std::span<std::uint8_t> b, std::size_t off, double v) {
  put_le(b, off, std::bit_cast<std::uint64_t>(v));
}

double get_f64(std::span<const std::uint8_t> b, std::size_t off) {
  return std::bit_cast<double>(get_le<std::uint64_t>(b, off));
}

template <std::size_t N>
void put_f64s(std::span<std::uint8_t> b, std::size_t off, const std::array<double, N>& v) {
  for (std::size_t i = 0; i < N; ++i) put_f64(b, off + 8 * i, v[i]);
}

template <std::size_t N>
void get_f64s(std::span<const std::uint8_t> b, std::size_t off, std::array<double, N>& v) {
  for (std::size_t i = 0; i < N; ++i) v[i] = get_f64(b, off + 8 * i);
}

// ---- JSON numbers ------------------------------------------------------------------------

// The number grammar of RFC 8259 section 6: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?
// `integer` also refuses a fraction and an exponent.
bool is_json_number(std::string_view s, bool integer) {
  std::size_t i = 0;
  const auto digits = [&] {
    const std::size_t start = i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i;
    return i > start;
  };
  if (i < s.size() && s[i] == '-') ++i;
  if (i < s.size() && s[i] == '0') {
    ++i;
  } else if (!digits()) {
    return false;
  }
  if (i < s.size() && s[i] == '.') {
    if (integer) return false;
    ++i;
    if (!digits()) return false;
  }
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    if (integer) return false;
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    if (!digits()) return false;
  }
  return i == s.size();
}

// A plain (unquoted) YAML scalar holding a JSON number; quoted strings, null, true, arrays
// and objects are refused.
const std::string* number_text(const YAML::Node& n, bool integer) {
  if (!n.IsScalar() || n.Tag() != "?") return nullptr;
  const std::string& s = n.Scalar();
  return is_json_number(s, integer) ? &s : nullptr;
}

std::optional<double> to_double(const YAML::Node& n) {
  const std::string* s = number_text(n, false);
  if (s == nullptr) return std::nullopt;
  double v = 0.0;
  const auto r = std::from_chars(s->data(), s->data() + s->size(), v);
  if (r.ec != std::errc{} || r.ptr != s->data() + s->size() || !std::isfinite(v))
    return std::nullopt;  // out of range of double (1e999) is not a usable number either
  return v;
}

template <typename Int>
std::optional<Int> to_integer(const YAML::Node& n) {
  const std::string* s = number_text(n, true);
  if (s == nullptr) return std::nullopt;
  Int v = 0;
  const auto r = std::from_chars(s->data(), s->data() + s->size(), v);
  if (r.ec != std::errc{} || r.ptr != s->data() + s->size()) return std::nullopt;
  return v;
}

// Refuses what cannot be one flat JSON object before yaml-cpp sees it: text that does not
// start with '{' and end with '}', characters outside strings that JSON does not use (so
// that YAML-only syntax is not accepted), and any nesting (which also bounds the parser's
// recursion).
bool flat_object_shape(std::string_view t) {
  const auto first = t.find_first_not_of(" \t\r\n");
  const auto last = t.find_last_not_of(" \t\r\n");
  if (first == std::string_view::npos || t[first] != '{' || t[last] != '}') return false;
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = first; i <= last; ++i) {
    const char c = t[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (std::string_view(" \t\r\n,:+-.0123456789").find(c) == std::string_view::npos &&
               !(c >= 'a' && c <= 'z') && !(c >= 'A' && c <= 'Z') && c != '{' && c != '}' &&
               c != '[' && c != ']') {
      return false;  // YAML syntax outside strings: anchors, tags, comments, single quotes...
    } else if (c == '{' || c == '[') {
      if (++depth > 1) return false;
    } else if (c == '}' || c == ']') {
      if (--depth < 0) return false;
    }
  }
  return depth == 0 && !in_string;
}

// JSON keys: one slot each; the alternatives of a group are consecutive runs of slots.
// clang-format off
enum Key : std::size_t {
  kSeq, kVersionKey, kTGps, kTUnix,
  kLat, kLon, kH, kX, kY, kZ,
  kVn, kVe, kVd, kVx, kVy, kVz,
  kQw, kQx, kQy, kQz, kRoll, kPitch, kYaw,
  kFx, kFy, kFz, kWx, kWy, kWz,
  kTemperature,
  kKeyCount
};

constexpr std::array<std::string_view, kKeyCount> kKeyNames{
    "seq", "version", "t_gps_ns", "t_unix_ns",
    "lat_deg", "lon_deg", "h_m", "x_m", "y_m", "z_m",
    "v_n_mps", "v_e_mps", "v_d_mps", "vx_mps", "vy_mps", "vz_mps",
    "qw", "qx", "qy", "qz", "roll_deg", "pitch_deg", "yaw_deg",
    "f_x_mps2", "f_y_mps2", "f_z_mps2", "w_x_radps", "w_y_radps", "w_z_radps",
    "temperature_c"};
// clang-format on

struct Slots {
  std::array<bool, kKeyCount> present{};
  std::array<double, kKeyCount> value{};
  std::int64_t time_ns = 0;
  std::uint32_t seq = 0;

  // All of [begin, begin + n) present.
  bool all(std::size_t begin, std::size_t n) const {
    return std::all_of(present.begin() + static_cast<std::ptrdiff_t>(begin),
                       present.begin() + static_cast<std::ptrdiff_t>(begin + n),
                       [](bool b) { return b; });
  }
  bool none(std::size_t begin, std::size_t n) const {
    return std::none_of(present.begin() + static_cast<std::ptrdiff_t>(begin),
                        present.begin() + static_cast<std::ptrdiff_t>(begin + n),
                        [](bool b) { return b; });
  }
  // Which of two alternatives (first run of n slots at a, second of m at b) is complete, the
  // other being absent; nothing when neither or both or a partial one is given.
  std::optional<bool> choose(std::size_t a, std::size_t n, std::size_t b, std::size_t m) const {
    if (all(a, n) && none(b, m)) return false;
    if (all(b, m) && none(a, n)) return true;
    return std::nullopt;
  }
  template <std::size_t N>
  void copy(std::size_t begin, std::array<double, N>& to) const {
    for (std::size_t i = 0; i < N; ++i) to[i] = value[begin + i];
  }
};

DecodeResult read_slots(std::string_view text, Slots& s) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (...) {  // YAML::ParserException, and anything else the parser may throw
    return DecodeResult::kBadJson;
  }
  if (!root.IsMap()) return DecodeResult::kBadJson;
  for (const auto& kv : root) {
    const YAML::Node& key = kv.first;
    if (!key.IsScalar() || key.Tag() != "!") return DecodeResult::kBadJson;  // a JSON string
    const auto found = std::find(kKeyNames.begin(), kKeyNames.end(), key.Scalar());
    if (found == kKeyNames.end()) continue;  // unknown keys are ignored
    const auto k = static_cast<std::size_t>(found - kKeyNames.begin());
    if (s.present[k]) return DecodeResult::kBadJson;  // duplicate key
    s.present[k] = true;
    if (k == kSeq) {
      const auto v = to_integer<std::uint32_t>(kv.second);
      if (!v) return DecodeResult::kBadJson;
      s.seq = *v;
    } else if (k == kVersionKey) {
      const auto v = to_integer<std::int64_t>(kv.second);
      if (!v) return DecodeResult::kBadJson;
      if (*v != kVersion) return DecodeResult::kBadVersion;
    } else if (k == kTGps || k == kTUnix) {
      const auto v = to_integer<std::int64_t>(kv.second);
      if (!v) return DecodeResult::kBadJson;
      s.time_ns = *v;
    } else {
      const auto v = to_double(kv.second);
      if (!v) return DecodeResult::kBadJson;
      s.value[k] = *v;
    }
  }
  return DecodeResult::kOk;
}

}  // namespace

const char* to_string(DecodeResult r) {
  switch (r) {  // clang-format off
    case DecodeResult::kOk: return "ok";
    case DecodeResult::kBadLength: return "bad length";
    case DecodeResult::kBadMagic: return "bad magic";
    case DecodeResult::kBadVersion: return "bad version";
    case DecodeResult::kBadCrc: return "bad CRC";
    case DecodeResult::kBadJson: return "bad JSON";
    case DecodeResult::kMissingField: return "missing or conflicting field";
  }  // clang-format on
  return "unknown";
}

// Reflected CRC-32, polynomial 0x04C11DB7 (reversed 0xEDB88320), bit by bit.
std::uint32_t crc32(std::span<const std::uint8_t> bytes) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::uint8_t b : bytes) {
    crc ^= b;
    for (int i = 0; i < 8; ++i) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return crc ^ 0xFFFFFFFFu;
}

std::array<std::uint8_t, kBinarySize> encode_binary(const Message& m) {
  std::array<std::uint8_t, kBinarySize> a{};
  const std::span<std::uint8_t> b(a);
  std::copy(kMagic.begin(), kMagic.end(), a.begin());
  a[kOffVersion] = kVersion;
  a[kOffReserved] = 0;
  std::uint16_t flags = 0;
  if (m.time_base == TimeBase::kHostUtc) flags |= kFlagHostUtc;
  if (m.position_frame == PositionFrame::kEcef) flags |= kFlagPositionEcef;
  if (m.velocity_frame == VelocityFrame::kEcef) flags |= kFlagVelocityEcef;
  if (m.attitude_form == AttitudeForm::kRollPitchYaw) flags |= kFlagRollPitchYaw;
  if (m.has_rates) flags |= kFlagRates;
  if (m.has_temperature) flags |= kFlagTemperature;
  put_le(b, kOffFlags, flags);
  put_le(b, kOffSequence, m.sequence);
  put_le(b, kOffTime, static_cast<std::uint64_t>(m.time_ns));
  put_f64s(b, kOffPosition, m.position);
  put_f64s(b, kOffVelocity, m.velocity_mps);
  put_f64s(b, kOffAttitude, m.attitude);
  if (m.has_rates) {  // absent blocks stay zero
    put_f64s(b, kOffForce, m.f_body_mps2);
    put_f64s(b, kOffRate, m.w_body_radps);
  }
  if (m.has_temperature) put_f64(b, kOffTemperature, m.temperature_c);
  put_le(b, kCrcOffset, crc32(b.first(kCrcOffset)));
  return a;
}

// Checked in this order: magic (as far as there are bytes), enough bytes for the version, version
// (so that a datagram of another version is reported as such whatever its length), exact length,
// CRC, then the reserved byte and undefined flag bits, which version 1 requires to be zero.
DecodeResult decode_binary(std::span<const std::uint8_t> b, Message& out) {
  const std::size_t n = std::min(b.size(), kMagic.size());
  if (!std::equal(kMagic.begin(), kMagic.begin() + static_cast<std::ptrdiff_t>(n), b.begin()))
    return DecodeResult::kBadMagic;
  if (b.size() < kOffVersion + 1) return DecodeResult::kBadLength;
  if (b[kOffVersion] != kVersion) return DecodeResult::kBadVersion;
  if (b.size() != kBinarySize) return DecodeResult::kBadLength;
  if (crc32(b.first(kCrcOffset)) != get_le<std::uint32_t>(b, kCrcOffset))
    return DecodeResult::kBadCrc;
  const auto flags = get_le<std::uint16_t>(b, kOffFlags);
  if (b[kOffReserved] != 0 || (flags & ~kFlagsDefined) != 0) return DecodeResult::kBadVersion;

  Message m;
  m.time_base = (flags & kFlagHostUtc) != 0 ? TimeBase::kHostUtc : TimeBase::kGps;
  m.position_frame =
      (flags & kFlagPositionEcef) != 0 ? PositionFrame::kEcef : PositionFrame::kGeodetic;
  m.velocity_frame = (flags & kFlagVelocityEcef) != 0 ? VelocityFrame::kEcef : VelocityFrame::kNed;
  m.attitude_form =
      (flags & kFlagRollPitchYaw) != 0 ? AttitudeForm::kRollPitchYaw : AttitudeForm::kQuaternion;
  m.has_rates = (flags & kFlagRates) != 0;
  m.has_temperature = (flags & kFlagTemperature) != 0;
  m.sequence = get_le<std::uint32_t>(b, kOffSequence);
  m.time_ns = static_cast<std::int64_t>(get_le<std::uint64_t>(b, kOffTime));
  get_f64s(b, kOffPosition, m.position);
  get_f64s(b, kOffVelocity, m.velocity_mps);
  get_f64s(b, kOffAttitude, m.attitude);
  if (m.has_rates) {
    get_f64s(b, kOffForce, m.f_body_mps2);
    get_f64s(b, kOffRate, m.w_body_radps);
  }
  if (m.has_temperature) m.temperature_c = get_f64(b, kOffTemperature);
  out = m;
  return DecodeResult::kOk;
}

// Numbers in the shortest form that reads back to the same double; a non-finite value, which
// JSON cannot express, is written as null (and refused by decode_json).
std::string encode_json(const Message& m) {
  std::string s;
  auto out = std::back_inserter(s);
  const auto num = [&](std::string_view key, double v) {
    if (std::isfinite(v)) {
      fmt::format_to(out, ",\"{}\":{}", key, v);
    } else {
      fmt::format_to(out, ",\"{}\":null", key);
    }
  };
  fmt::format_to(out, "{{\"seq\":{}", m.sequence);
  fmt::format_to(out, ",\"{}\":{}", m.time_base == TimeBase::kGps ? "t_gps_ns" : "t_unix_ns",
                 m.time_ns);
  const std::size_t pos = m.position_frame == PositionFrame::kGeodetic ? kLat : kX;
  const std::size_t vel = m.velocity_frame == VelocityFrame::kNed ? kVn : kVx;
  for (std::size_t i = 0; i < 3; ++i) num(kKeyNames[pos + i], m.position[i]);
  for (std::size_t i = 0; i < 3; ++i) num(kKeyNames[vel + i], m.velocity_mps[i]);
  if (m.attitude_form == AttitudeForm::kQuaternion) {
    for (std::size_t i = 0; i < 4; ++i) num(kKeyNames[kQw + i], m.attitude[i]);
  } else {
    for (std::size_t i = 0; i < 3; ++i) num(kKeyNames[kRoll + i], m.attitude[i]);
  }
  if (m.has_rates) {
    for (std::size_t i = 0; i < 3; ++i) num(kKeyNames[kFx + i], m.f_body_mps2[i]);
    for (std::size_t i = 0; i < 3; ++i) num(kKeyNames[kWx + i], m.w_body_radps[i]);
  }
  if (m.has_temperature) num(kKeyNames[kTemperature], m.temperature_c);
  s += '}';
  return s;
}

DecodeResult decode_json(std::string_view text, Message& out) {
  if (text.size() > kMaxJson) return DecodeResult::kBadLength;
  if (!flat_object_shape(text)) return DecodeResult::kBadJson;
  Slots s;
  if (const DecodeResult r = read_slots(text, s); r != DecodeResult::kOk) return r;

  const auto time = s.choose(kTGps, 1, kTUnix, 1);
  const auto pos = s.choose(kLat, 3, kX, 3);
  const auto vel = s.choose(kVn, 3, kVx, 3);
  const auto att = s.choose(kQw, 4, kRoll, 3);
  const bool rates_ok = s.all(kFx, 6) || s.none(kFx, 6);
  if (!s.present[kSeq] || !time || !pos || !vel || !att || !rates_ok)
    return DecodeResult::kMissingField;

  Message m;
  m.sequence = s.seq;
  m.time_base = *time ? TimeBase::kHostUtc : TimeBase::kGps;
  m.time_ns = s.time_ns;
  m.position_frame = *pos ? PositionFrame::kEcef : PositionFrame::kGeodetic;
  s.copy(*pos ? kX : kLat, m.position);
  m.velocity_frame = *vel ? VelocityFrame::kEcef : VelocityFrame::kNed;
  s.copy(*vel ? kVx : kVn, m.velocity_mps);
  m.attitude_form = *att ? AttitudeForm::kRollPitchYaw : AttitudeForm::kQuaternion;
  if (*att) {
    m.attitude = {s.value[kRoll], s.value[kPitch], s.value[kYaw], 0.0};
  } else {
    s.copy(kQw, m.attitude);
  }
  m.has_rates = s.present[kFx];
  if (m.has_rates) {
    s.copy(kFx, m.f_body_mps2);
    s.copy(kWx, m.w_body_radps);
  }
  m.has_temperature = s.present[kTemperature];
  if (m.has_temperature) m.temperature_c = s.value[kTemperature];
  out = m;
  return DecodeResult::kOk;
}

DecodeResult decode(std::span<const std::uint8_t> bytes, Message& out) {
  if (bytes.empty()) return DecodeResult::kBadLength;
  if (bytes[0] == '{') {
    if (bytes.size() > kMaxJson) return DecodeResult::kBadLength;
    return decode_json(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                       out);
  }
  return decode_binary(bytes, out);  // kBadMagic unless it starts with "NVTR"
}

}  // namespace navemu::truth_datagram
