#pragma once
// AST of one NC line as the X3 grammar produces it (grammar/gcode_def.hpp).
//
// Every construct of a line is an Item made of two spans into the line:
//   head  the character(s) that introduce it: a word letter, 'N', 'O', '/',
//         '%', '*' (checksum), '(' or ';' (comments);
//   body  the text that follows: the number of a word (sign and blanks
//         included, exactly as written), the digits of N/O/'*', the text
//         inside a comment; empty for '/' and '%'.
// src/gcode/parser.cpp turns the items into an abbe::gcode::Block. Spans keep
// the byte offsets the post-processor needs to rewrite one number in place.
#include <boost/range/iterator_range_core.hpp>
#include <vector>

namespace abbe::gcode::ast {

using Iterator = const char*;
using Span = boost::iterator_range<Iterator>;

struct Item {
  Span head;
  Span body;
};

// The items of one line in the order written.
using Line = std::vector<Item>;

}  // namespace abbe::gcode::ast
