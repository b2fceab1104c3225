#pragma once
// InputError: the one error type for bad user input (NC programs, machine
// files, tables, measured data). It always names the file and, where known,
// the line and column (1-based) or the field, and can show the offending
// source line with a caret under the column.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace abbe {

struct SourceLocation {
  std::string file;         // "-" for standard input, "<string>" for in-memory text
  std::size_t line = 0;     // 1-based; 0 = unknown
  std::size_t column = 0;   // 1-based; 0 = unknown
  std::string field;        // a named field (YAML key, CSV column), empty if none
  std::string source_line;  // the text of the line, for the caret display; may be empty
};

class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation where, const std::string& message);

  const SourceLocation& where() const noexcept { return where_; }
  const std::string& message() const noexcept { return message_; }

 private:
  SourceLocation where_;
  std::string message_;
};

// "file:line:col: error: message" followed, when the source line is known,
// by the line and a caret under the column (tabs kept so the caret aligns).
std::string format_input_error(const SourceLocation& where, const std::string& message);

}  // namespace abbe
