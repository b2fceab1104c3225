#pragma once
// The pieces of io::CsvReader (csv_reader.hpp), the one CSV reader of abbe:
// a field that remembers its 1-based start column (for file:line:col
// errors), and trimming of blanks (and the CR of CRLF files).
#include <cstddef>
#include <string_view>

namespace abbe::io {

struct CsvField {
  std::string_view text;  // as written, untrimmed
  std::size_t column;     // 1-based column of its first character
};

// Without leading spaces/tabs and trailing spaces/tabs/CR.
std::string_view trim_blanks(std::string_view s);

}  // namespace abbe::io
