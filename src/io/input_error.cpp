#include "abbe/io/input_error.hpp"

#include <fmt/format.h>

namespace abbe {

namespace {
constexpr std::size_t kMaxShownLine = 160;  // long lines are shown around the column
}

std::string format_input_error(const SourceLocation& where, const std::string& message) {
  std::string out = where.file.empty() ? std::string("<input>") : where.file;
  if (where.line > 0) out += fmt::format(":{}", where.line);
  if (where.column > 0) out += fmt::format(":{}", where.column);
  if (!where.field.empty()) out += fmt::format(" [{}]", where.field);
  out += ": error: " + message;
  if (!where.source_line.empty() && where.column > 0) {
    // Show at most kMaxShownLine characters around the column.
    std::size_t col0 = where.column - 1;
    std::size_t begin = 0;
    if (where.source_line.size() > kMaxShownLine && col0 > kMaxShownLine / 2)
      begin = col0 - kMaxShownLine / 2;
    std::string shown = where.source_line.substr(begin, kMaxShownLine);
    // Replace control characters (binary garbage) so the terminal stays sane.
    for (char& c : shown) {
      unsigned char u = static_cast<unsigned char>(c);
      if (u < 0x20 && c != '\t') c = '?';
      if (u == 0x7f) c = '?';
    }
    std::string caret;
    for (std::size_t i = begin; i < col0 && i < where.source_line.size(); ++i)
      caret += where.source_line[i] == '\t' ? '\t' : ' ';
    caret += '^';
    out += "\n  " + shown + "\n  " + caret;
  }
  return out;
}

InputError::InputError(SourceLocation where, const std::string& message)
    : std::runtime_error(format_input_error(where, message)),
      where_(std::move(where)),
      message_(message) {}

}  // namespace abbe
