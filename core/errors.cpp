#include "core/errors.hpp"

#include <fmt/format.h>

namespace navemu {

namespace {
std::string compose(const std::string& file, int line, const std::string& field,
                    const std::string& problem) {
  std::string out;
  if (!file.empty()) out += file + ":";
  if (line > 0) out += fmt::format("{}:", line);
  if (!out.empty()) out += " ";
  if (!field.empty()) out += field + ": ";
  out += problem;
  return out;
}
}  // namespace

InputError::InputError(std::string file, int line, std::string field, const std::string& problem)
    : std::runtime_error(compose(file, line, field, problem)),
      file_(std::move(file)),
      line_(line),
      field_(std::move(field)) {}

InputError::InputError(std::string field, const std::string& problem)
    : InputError("", 0, std::move(field), problem) {}

}  // namespace navemu
