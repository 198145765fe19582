#include "emulator/numeric_csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string_view>

#include "core/errors.hpp"

namespace navemu {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

bool skippable(std::string_view line) {
  const std::string_view t = trim(line);
  return t.empty() || t.front() == '#';
}

}  // namespace

NumericCsvReader::NumericCsvReader(std::string path, std::vector<std::string> columns,
                                   std::vector<std::string> optional_columns,
                                   std::optional<std::string> increasing)
    : path_(std::move(path)), in_(path_) {
  if (!in_) throw InputError(path_, 0, "", "cannot open for reading");
  std::string header;
  bool found = false;
  while (read_line(header)) {
    ++line_;
    if (!skippable(header)) {
      found = true;
      break;
    }
  }
  if (!found) throw InputError(path_, line_, "", "no header row");
  std::vector<std::string> fields;
  for (std::string_view rest = header;;) {
    const std::size_t comma = rest.find(',');
    fields.emplace_back(trim(rest.substr(0, comma)));
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  auto field_index = [&](const std::string& name) -> std::optional<std::size_t> {
    const auto it = std::find(fields.begin(), fields.end(), name);
    if (it == fields.end()) return std::nullopt;
    if (std::find(it + 1, fields.end(), name) != fields.end())
      throw InputError(path_, line_, name, "column named twice in the header");
    return static_cast<std::size_t>(it - fields.begin());
  };
  for (const std::string& name : columns) {
    const auto i = field_index(name);
    if (!i) {
      std::string have;
      for (const std::string& f : fields) have += (have.empty() ? "" : ",") + f;
      throw InputError(path_, line_, name, fmt::format("missing column (the header has: {})", have));
    }
    if (std::find(field_of_.begin(), field_of_.end(), *i) != field_of_.end())
      throw InputError(path_, line_, name, "column requested twice");
    names_.push_back(name);
    field_of_.push_back(*i);
  }
  for (const std::string& name : optional_columns) {
    const auto i = field_index(name);
    if (!i) continue;
    names_.push_back(name);
    field_of_.push_back(*i);
  }
  for (std::size_t f : field_of_) needed_fields_ = std::max(needed_fields_, f + 1);
  if (increasing) {
    const auto it = std::find(names_.begin(), names_.end(), *increasing);
    if (it != names_.end()) increasing_ = static_cast<std::size_t>(it - names_.begin());
  }
}

// As std::getline, but a line over kMaxLineBytes is an error rather than an unbounded read.
bool NumericCsvReader::read_line(std::string& line) {
  line.clear();
  std::streambuf& in = *in_.rdbuf();
  for (int c = in.sbumpc(); c != std::char_traits<char>::eof(); c = in.sbumpc()) {
    if (c == '\n') return true;
    if (line.size() == kMaxLineBytes)
      throw InputError(path_, line_ + 1, "", fmt::format("line longer than {} bytes", kMaxLineBytes));
    line.push_back(static_cast<char>(c));
  }
  return !line.empty();
}

bool NumericCsvReader::has(const std::string& optional_column) const {
  return std::find(names_.begin(), names_.end(), optional_column) != names_.end();
}

bool NumericCsvReader::next(std::vector<double>& values) {
  while (read_line(row_)) {
    ++line_;
    if (skippable(row_)) continue;
    // Split only as far as the last field needed.
    std::vector<std::string_view> cells;
    cells.reserve(needed_fields_);
    std::string_view rest = row_;
    while (cells.size() < needed_fields_) {
      const std::size_t comma = rest.find(',');
      cells.push_back(trim(rest.substr(0, comma)));
      if (comma == std::string_view::npos) break;
      rest.remove_prefix(comma + 1);
    }
    values.resize(names_.size());
    for (std::size_t c = 0; c < names_.size(); ++c) {
      if (field_of_[c] >= cells.size())
        throw InputError(path_, line_, names_[c],
                         fmt::format("missing value (the row has {} fields)", cells.size()));
      const std::string_view text = cells[field_of_[c]];
      if (text.empty()) throw InputError(path_, line_, names_[c], "empty value");
      double x = 0.0;
      const char* first = text.data() + (text.front() == '+' ? 1 : 0);  // from_chars takes no '+'
      const auto [end, ec] = std::from_chars(first, text.data() + text.size(), x);
      if (ec == std::errc::result_out_of_range)
        throw InputError(path_, line_, names_[c], fmt::format("not a finite number: '{}'", text));
      if (ec != std::errc() || end != text.data() + text.size())
        throw InputError(path_, line_, names_[c], fmt::format("not a number: '{}'", text));
      if (!std::isfinite(x))
        throw InputError(path_, line_, names_[c], fmt::format("not a finite number: '{}'", text));
      values[c] = x;
    }
    if (increasing_) {
      const double v = values[*increasing_];
      if (last_increasing_ && !(v > *last_increasing_))
        throw InputError(path_, line_, names_[*increasing_],
                         fmt::format("time {} s does not increase (previous row {} s)", v,
                                     *last_increasing_));
      last_increasing_ = v;
    }
    return true;
  }
  return false;
}

}  // namespace navemu
