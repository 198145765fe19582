#include "emulator/yaml_reader.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "core/errors.hpp"

namespace navemu {

YamlMap::YamlMap(std::filesystem::path file, const YAML::Node& node, std::string where)
    : file_(std::move(file)), node_(node), where_(std::move(where)) {
  if (node_ && !node_.IsNull() && !node_.IsMap()) fail("", "expected a mapping of keys to values");
}

void YamlMap::fail(const std::string& key, const std::string& problem) const {
  YAML::Mark mark = node_ ? node_.Mark() : YAML::Mark::null_mark();
  if (!key.empty() && node_ && node_.IsMap()) {
    // The key's own line, when the key is there.
    for (const auto& kv : node_)
      if (kv.first.Scalar() == key) mark = kv.first.Mark();
  }
  std::string field = where_;
  if (!key.empty()) field = field.empty() ? key : field + "." + key;
  throw InputError(file_.string(), mark.is_null() ? 0 : mark.line + 1, field, problem);
}

bool YamlMap::has(const std::string& key) const {
  return node_ && node_.IsMap() && node_[key] && !node_[key].IsNull();
}

std::optional<YAML::Node> YamlMap::value(const std::string& key) {
  read_.insert(key);
  if (!has(key)) return std::nullopt;
  const YAML::Node& n = node_;
  return n[key];
}

std::optional<std::string> YamlMap::text(const std::string& key) {
  const std::optional<YAML::Node> o = value(key);
  if (!o) return std::nullopt;
  const YAML::Node& v = *o;
  if (!v.IsScalar()) fail(key, "expected a text value");
  return v.Scalar();
}

std::optional<double> YamlMap::number(const std::string& key) {
  const std::optional<YAML::Node> o = value(key);
  if (!o) return std::nullopt;
  const YAML::Node& v = *o;
  double x = 0.0;
  try {
    if (!v.IsScalar()) throw YAML::Exception(v.Mark(), "");
    x = v.as<double>();
  } catch (const YAML::Exception&) {
    fail(key, fmt::format("'{}' is not a number", v.IsScalar() ? v.Scalar() : "(not a scalar)"));
  }
  if (!std::isfinite(x)) fail(key, fmt::format("'{}' is not finite", v.Scalar()));
  return x;
}

std::optional<double> YamlMap::positive(const std::string& key, bool allow_zero) {
  const std::optional<double> x = number(key);
  if (x && (*x < 0.0 || (*x == 0.0 && !allow_zero)))
    fail(key, fmt::format("must be {} (got {})", allow_zero ? "zero or more" : "positive", *x));
  return x;
}

std::optional<std::int64_t> YamlMap::integer(const std::string& key, std::int64_t min,
                                             std::int64_t max) {
  const std::optional<YAML::Node> o = value(key);
  if (!o) return std::nullopt;
  const YAML::Node& v = *o;
  std::int64_t x = 0;
  try {
    if (!v.IsScalar()) throw YAML::Exception(v.Mark(), "");
    x = v.as<std::int64_t>();
  } catch (const YAML::Exception&) {
    fail(key, fmt::format("'{}' is not an integer", v.IsScalar() ? v.Scalar() : "(not a scalar)"));
  }
  if (x < min || x > max) fail(key, fmt::format("{} outside [{}, {}]", x, min, max));
  return x;
}

std::optional<bool> YamlMap::boolean(const std::string& key) {
  const std::optional<YAML::Node> o = value(key);
  if (!o) return std::nullopt;
  const YAML::Node& v = *o;
  try {
    if (!v.IsScalar()) throw YAML::Exception(v.Mark(), "");
    return v.as<bool>();
  } catch (const YAML::Exception&) {
    fail(key, fmt::format("'{}' is not true or false", v.IsScalar() ? v.Scalar() : "(not a scalar)"));
  }
}

std::optional<std::vector<std::string>> YamlMap::text_list(const std::string& key) {
  const std::optional<YAML::Node> o = value(key);
  if (!o) return std::nullopt;
  const YAML::Node& v = *o;
  if (!v.IsSequence()) fail(key, "expected a list, e.g. [RMC, GGA]");
  std::vector<std::string> out;
  for (const auto& item : v) {
    if (!item.IsScalar()) fail(key, "expected a list of text values");
    out.push_back(item.Scalar());
  }
  return out;
}

double YamlMap::finite_number(const std::string& key, const std::string& text) const {
  double x = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(x))
    fail(key, fmt::format("'{}' is not a number", text));
  return x;
}

std::optional<std::vector<double>> YamlMap::number_list(const std::string& key) {
  const std::optional<std::vector<std::string>> texts = text_list(key);
  if (!texts) return std::nullopt;
  std::vector<double> out;
  for (const std::string& t : *texts) out.push_back(finite_number(key, t));
  return out;
}

std::optional<std::vector<std::pair<double, double>>> YamlMap::number_pairs(const std::string& key) {
  const std::optional<YAML::Node> o = value(key);
  if (!o) return std::nullopt;
  const auto bad = [&] { fail(key, "expected a list of [number, number] pairs, e.g. [[0, -13], [90, 0]]"); };
  if (!o->IsSequence()) bad();
  std::vector<std::pair<double, double>> out;
  for (const auto& item : *o) {
    if (!item.IsSequence() || item.size() != 2 || !item[0].IsScalar() || !item[1].IsScalar()) bad();
    out.emplace_back(finite_number(key, item[0].Scalar()), finite_number(key, item[1].Scalar()));
  }
  return out;
}

YamlMap YamlMap::map(const std::string& key) {
  const std::optional<YAML::Node> v = value(key);
  std::string where = where_.empty() ? key : where_ + "." + key;
  if (v && !v->IsMap()) fail(key, "expected a mapping of keys to values");
  return YamlMap(file_, v ? *v : YAML::Node(), std::move(where));
}

std::vector<YamlMap> YamlMap::map_list(const std::string& key) {
  const std::optional<YAML::Node> o = value(key);
  std::vector<YamlMap> out;
  if (!o) return out;
  const YAML::Node& v = *o;
  if (!v.IsSequence()) fail(key, "expected a list of mappings");
  std::size_t i = 0;
  for (const auto& item : v) {
    const std::string where = fmt::format("{}{}[{}]", where_.empty() ? "" : where_ + ".", key, i++);
    if (!item.IsMap()) YamlMap(file_, item, where).fail("", "expected a mapping");
    out.emplace_back(file_, item, where);
  }
  return out;
}

void YamlMap::reject_unknown_keys() const {
  if (!node_ || !node_.IsMap()) return;
  for (const auto& kv : node_) {
    const std::string key = kv.first.Scalar();
    if (read_.count(key) == 0) {
      std::string known;
      for (const std::string& k : read_) known += (known.empty() ? "" : ", ") + k;
      fail(key, fmt::format("unknown key (known here: {})", known));
    }
  }
}

namespace {

// Where the first byte that cannot be in a YAML text file lies (a NUL or another control
// character than tab, CR and LF, or malformed UTF-8: YAML 1.2 section 5.1), as "line L, column
// C (byte 0xNN)"; empty for text.
std::string first_binary_byte(const std::string& text) {
  int line = 1, column = 1;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    std::size_t len = c < 0x80 ? 1 : (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 : (c & 0xF8) == 0xF0 ? 4 : 0;
    bool ok = len != 0 && i + len <= text.size() && (c >= 0x20 || c == '\t' || c == '\n' || c == '\r') &&
              c != 0x7F && (len != 2 || c >= 0xC2);
    for (std::size_t k = 1; ok && k < len; ++k) ok = (static_cast<unsigned char>(text[i + k]) & 0xC0) == 0x80;
    if (!ok) return fmt::format("line {}, column {} (byte 0x{:02X})", line, column, c);
    if (c == '\n') {
      ++line;
      column = 0;
    }
    ++column;
    i += len;
  }
  return "";
}

}  // namespace

YAML::Node parse_yaml_file(const std::filesystem::path& file, const char* what) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw InputError(file.string(), 0, "", fmt::format("is a folder, not a {} file", what));
  if (!std::filesystem::exists(file, ec))
    throw InputError(file.string(), 0, "", fmt::format("no such {} file", what));
  if (!std::filesystem::is_regular_file(file, ec))
    throw InputError(file.string(), 0, "", fmt::format("not a regular file: a {} file is YAML text", what));
  // yaml-cpp builds the whole document as nodes (about 100 bytes per scalar): a bound, so that
  // a wrong file is an error rather than memory exhausted. Configurations are a few kB.
  constexpr std::uintmax_t kMaxBytes = 16u << 20;
  if (const std::uintmax_t size = std::filesystem::file_size(file, ec); !ec && size > kMaxBytes)
    throw InputError(file.string(), 0, "",
                     fmt::format("{} bytes: over the 16 MiB a {} file may have", size, what));
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), 0, "", fmt::format("cannot be opened ({})", std::strerror(errno)));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(file.string(), 0, "", fmt::format("cannot be read ({})", std::strerror(errno)));
  if (const std::string where = first_binary_byte(text); !where.empty())
    throw InputError(file.string(), 0, "",
                     fmt::format("not a text file: {} cannot be in YAML; is this the {} file?", where, what));
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(file.string(), e.mark.line + 1, "", "YAML syntax error: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw InputError(file.string(), 0, "", e.what());
  }
}

YamlMap load_yaml_file(const std::filesystem::path& file) {
  return YamlMap(file, parse_yaml_file(file, "configuration"), "");
}

}  // namespace navemu
