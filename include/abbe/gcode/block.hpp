#pragma once
// Block: one parsed line of an NC program. Positions are byte offsets into the
// original line so that a post-processor can replace a coordinate's number and
// keep every other byte of the line.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "abbe/gcode/expression.hpp"

namespace abbe::gcode {

struct Word {
  char letter = 0;                 // upper-case letter
  double value = 0.0;              // the number as written (program units)
  std::uint32_t begin = 0;         // offset of the letter in the line
  std::uint32_t number_begin = 0;  // offset of the first character of the number (sign included)
  std::uint32_t end = 0;           // one past the last character of the number
};

struct Comment {
  std::uint32_t begin = 0;  // offset of '(' or ';'
  std::uint32_t end = 0;    // one past ')' or end of line
  std::string text;         // inside the delimiters
};

struct Block {
  std::size_t line = 0;                // 1-based line number in the file
  bool block_delete = false;           // leading '/'
  bool percent = false;                // a '%' tape delimiter line
  std::optional<long> program_number;  // an O-number line (O1234), program number only
  std::optional<Word> n;               // N line number, if any
  std::vector<Word> words;             // all words but N, in the order written
  std::vector<Comment> comments;
  std::optional<int> checksum;  // *nn

  // Parameters, expressions and O-words (LinuxCNC dialect,
  // gcode/expression.hpp): all empty for a plain block.
  std::vector<ExprCode> code;                    // the postfix code of every expression
  std::vector<std::string> names;                // named parameters the code refers to
  std::vector<WordExpression> word_expressions;  // words whose value is computed
  std::vector<ParameterSetting> settings;        // #n = ..., in the order written
  OWord o;                                       // o.keyword == none: no O-word

  bool has_code() const { return !code.empty() || !names.empty() || o.keyword != OKeyword::none; }
};

}  // namespace abbe::gcode
