#pragma once
// What the X3 grammar (grammar/gcode_def.hpp) produces for one NC line.
//
// The grammar does not build a tree: its semantic actions write every
// construct straight into an abbe::gcode::Block (grammar/line_actions.hpp),
// with the byte offsets the post-processor needs to rewrite one number in
// place. `Line` is the attribute of the line rule: the Block being filled,
// what the error explanation needs to know about the items stored so far,
// and the first number that could not be converted.
#include <boost/range/iterator_range_core.hpp>
#include <cstddef>
#include <cstdint>

#include "abbe/gcode/block.hpp"

namespace abbe::gcode::ast {

using Iterator = const char*;
using Span = boost::iterator_range<Iterator>;

// A number scanned once by number_parser (grammar/primitives.hpp): its text
// and what the conversion to double needs.
struct Number {
  Iterator begin = nullptr;    // the sign if any, else the first digit or '.'
  Iterator end = nullptr;      // one past the last digit or '.'
  std::uint64_t mantissa = 0;  // the first 19 digits as an integer
  std::uint32_t digits = 0;    // number of digits
  std::uint32_t fraction = 0;  // number of digits after the '.'
  bool negative = false;
  bool point = false;  // a '.' was written
};

// Why a number of a well-formed line is refused (found while parsing,
// reported only once the whole line is known to be well-formed).
enum class NumberError : std::uint8_t {
  none,
  too_long,                  // more than 64 digits and '.'
  out_of_range,              // not a finite double
  program_number_too_large,  // O
  checksum_too_large,        // *
};

struct Line {
  Block* block = nullptr;         // filled by the semantic actions
  Iterator line_begin = nullptr;  // offsets are counted from here

  // Items stored so far (words, comments, N, O, '/', '%', '*'): how many,
  // how many of them are words and comments, the head character of the last
  // one ('(' or ';' for comments) and where the O of a program number is.
  std::size_t items = 0;
  std::size_t words_and_comments = 0;
  char last_head = 0;
  Iterator program_number_head = nullptr;

  std::size_t n_comments = 0;  // comments stored in block->comments (reused strings)

  NumberError error = NumberError::none;
  Iterator error_at = nullptr;

  // Expressions: where the code of the item being parsed begins in
  // block->code, where the index of a parameter setting ends, and the name
  // of a setting's #<name> (-1 for #n).
  std::uint32_t code_mark = 0;
  std::uint32_t target_end = 0;
  std::int32_t target_name = -1;
  // The furthest column an expression was read up to (for the message of a
  // line whose expression is malformed), or nullptr.
  Iterator expression_reach = nullptr;
};

// The tag under which the grammar's context carries the Line being filled
// (x3::with, see src/gcode/parser.cpp): actions inside the nested rules of
// expressions reach it through the context.
struct line_tag;

}  // namespace abbe::gcode::ast
