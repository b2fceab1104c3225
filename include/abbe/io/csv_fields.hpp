#pragma once
// The pieces every CSV reader of abbe shares: a line split at commas into
// fields that remember their 1-based start column (for file:line:col
// errors), and trimming of blanks (and the CR of CRLF files).
#include <cstddef>
#include <string_view>
#include <vector>

namespace abbe::io {

struct CsvField {
  std::string_view text;  // as written, untrimmed
  std::size_t column;     // 1-based column of its first character
};

// Without leading spaces/tabs and trailing spaces/tabs/CR.
std::string_view trim_blanks(std::string_view s);

// The fields of one line (an empty line gives one empty field).
std::vector<CsvField> split_csv_line(std::string_view line);

}  // namespace abbe::io
