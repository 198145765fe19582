#pragma once
// Errors for bad input files and bad user input: one line naming file, line and field.

#include <stdexcept>
#include <string>

namespace navemu {

// Thrown by every reader of user-supplied files (RINEX, CSV, ...) and by parsers of
// command-line values. what() is a complete one-line message:
//   "<file>:<line>: <field>: <problem>"   (line and field omitted when unknown)
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, int line, std::string field, const std::string& problem);
  // For values that do not come from a file (command-line options).
  InputError(std::string field, const std::string& problem);

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& field() const { return field_; }

 private:
  std::string file_;
  int line_ = 0;
  std::string field_;
};

}  // namespace navemu
