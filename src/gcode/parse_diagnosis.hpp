#pragma once
// Explains why a line is not in the language of grammar/gcode.ebnf: the
// grammar consumes the longest valid prefix of a line, and this looks at the
// text where it stopped to name the construct and its column.
#include <cstddef>
#include <string>
#include <string_view>

#include "abbe/io/input_error.hpp"
#include "grammar/ast.hpp"

namespace abbe::gcode::detail {

// An InputError at byte `offset` (0-based) of `line`.
InputError line_error(std::string_view line, std::size_t line_number, const std::string& file,
                      std::size_t offset, const std::string& message);

// The error for a line whose parse stopped at byte `stop` (< line.size())
// after storing `items`.
InputError explain_parse_stop(std::string_view line, std::size_t stop, const ast::Line& items,
                              std::size_t line_number, const std::string& file);

}  // namespace abbe::gcode::detail
