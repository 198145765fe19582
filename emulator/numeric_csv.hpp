#pragma once
// A streaming reader of numeric CSV files with a header row (IMU sample files, truth files).
// Columns are found by name in any order and extra columns are ignored; blank lines and lines
// starting with '#' are skipped; every value must be a finite number; a line may hold at most
// kMaxLineBytes (a file without line ends is refused, not read whole). Errors are InputError
// naming file, line and column.

#include <fstream>
#include <optional>
#include <string>
#include <vector>

namespace navemu {

class NumericCsvReader {
 public:
  static constexpr std::size_t kMaxLineBytes = 64 * 1024;

  // `columns`: required names; `optional_columns`: read when the header has them. When
  // `increasing` names a time column (seconds), its values must increase from row to row.
  NumericCsvReader(std::string path, std::vector<std::string> columns,
                   std::vector<std::string> optional_columns = {},
                   std::optional<std::string> increasing = std::nullopt);

  // The next row's values: the required columns in order, then the optional columns the header
  // has (see has()); false at the end of the file.
  bool next(std::vector<double>& values);

  bool has(const std::string& optional_column) const;
  const std::string& path() const { return path_; }
  int line() const { return line_; }  // line of the row last read

 private:
  std::string path_;
  bool read_line(std::string& line);  // the next line, bounded; false at the end of the file

  std::ifstream in_;
  int line_ = 0;
  std::vector<std::string> names_;      // the columns read, in output order
  std::vector<std::size_t> field_of_;   // their field index in a row
  std::size_t needed_fields_ = 0;
  std::optional<std::size_t> increasing_;  // index into names_
  std::optional<double> last_increasing_;
  std::string row_;
};

}  // namespace navemu
