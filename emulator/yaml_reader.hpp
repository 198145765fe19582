#pragma once
// Reading one YAML mapping of a configuration file with file:line errors: typed getters that
// remember which keys were read, and a final check that rejects every key nobody asked for (a
// misspelt key is an error, not a silently ignored setting).

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace navemu {

class YamlMap {
 public:
  // `node` must be a mapping (or null: an empty section); `where` names it in errors
  // ("gnss", "truth.circle").
  YamlMap(std::filesystem::path file, const YAML::Node& node, std::string where);

  bool has(const std::string& key) const;
  bool empty() const { return !node_.IsMap() || node_.size() == 0; }
  std::optional<std::string> text(const std::string& key);
  std::optional<double> number(const std::string& key);
  // A number that must be positive (or >= 0 with allow_zero).
  std::optional<double> positive(const std::string& key, bool allow_zero = false);
  std::optional<std::int64_t> integer(const std::string& key, std::int64_t min, std::int64_t max);
  std::optional<bool> boolean(const std::string& key);
  std::optional<std::vector<std::string>> text_list(const std::string& key);
  std::optional<std::vector<double>> number_list(const std::string& key);  // finite numbers
  // A list of two-number lists, e.g. [[0, -13], [90, 0]].
  std::optional<std::vector<std::pair<double, double>>> number_pairs(const std::string& key);
  // A nested mapping (empty when absent).
  YamlMap map(const std::string& key);
  // A list of mappings.
  std::vector<YamlMap> map_list(const std::string& key);
  // Throws for the first key that was never read.
  void reject_unknown_keys() const;

  // InputError "<file>:<line of key>: <where>.<key>: <problem>".
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;

  const std::filesystem::path& file() const { return file_; }

 private:
  std::optional<YAML::Node> value(const std::string& key);
  // `text` as a finite number, else fail(key, ...).
  double finite_number(const std::string& key, const std::string& text) const;
  std::filesystem::path file_;
  YAML::Node node_;
  std::string where_;
  std::set<std::string> read_;
};

// Parses a whole file; InputError "<file>: no such <what> file" or "<file>:<line>: YAML syntax
// error: ...".
YAML::Node parse_yaml_file(const std::filesystem::path& file, const char* what);
// The file's top-level mapping.
YamlMap load_yaml_file(const std::filesystem::path& file);

}  // namespace navemu
