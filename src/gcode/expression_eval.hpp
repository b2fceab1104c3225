#pragma once
// Evaluates the postfix code of an expression (gcode/expression.hpp) with
// rs274ngc's semantics: angles in degrees, EQ/NE within 1e-4, AND/OR/XOR on
// "not zero", MOD with a non-negative result, and its errors (division by
// zero, ACOS/ASIN/LN/SQRT/** out of domain, parameter number out of range,
// undefined named parameter), each naming file, line and column.
#include <string>
#include <string_view>

#include "abbe/gcode/block.hpp"
#include "parameters.hpp"

namespace abbe::gcode::detail {

struct CodeSite {
  const std::string& file;
  std::size_t line;
  std::string_view text;  // the line, for the caret display
};

[[noreturn]] void fail_at(const CodeSite& site, std::uint32_t column, const std::string& message);

double evaluate(const Block& block, CodeRange code, const ParameterStore& parameters,
                const CodeSite& site);

// A value that must be an integer (rs274: within 1e-4 of one), e.g. a parameter number.
int integer_value(double value, const CodeSite& site, std::uint32_t column, const char* what);

}  // namespace abbe::gcode::detail
