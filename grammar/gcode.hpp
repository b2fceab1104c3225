#pragma once
// Declaration of the line rule (definition in grammar/gcode_def.hpp, one
// instantiation in src/gcode/gcode_grammar.cpp). See grammar/gcode.ebnf.
#include <boost/spirit/home/x3.hpp>
#include <cstddef>

#include "grammar/ast.hpp"

namespace abbe::gcode::grammar {

namespace x3 = boost::spirit::x3;

// At most this many words and comments in one block (not counting N, '/', '*'):
// bounds the memory a single absurd line can take.
inline constexpr std::size_t kMaxItemsPerBlock = 1024;

// Numbers longer than this (digits and '.') are refused: no CAM post emits
// them and they can only be garbage.
inline constexpr std::size_t kMaxNumberChars = 64;

// Largest program number and checksum.
inline constexpr long kMaxProgramNumber = 999'999'999L;

struct line_class;
using line_type = x3::rule<line_class, ast::Line>;
BOOST_SPIRIT_DECLARE(line_type)

// The rule for one line. It always succeeds and consumes the longest prefix
// of the line that belongs to the language, storing its items into the
// attribute's Block as it goes; the caller checks that the whole line was
// consumed and otherwise explains why not (src/gcode/parser.cpp).
const line_type& line();

}  // namespace abbe::gcode::grammar
