#pragma once
// Line-by-line G-code parser (Boost.Spirit X3, grammar in grammar/).
// parse_line() turns one line into a Block or throws abbe::InputError naming
// file, line and column. Constructs abbe does not support (#parameters,
// [expressions], O-word control flow) are refused here with their name.
#include <istream>
#include <string>
#include <string_view>

#include "abbe/gcode/block.hpp"

namespace abbe::gcode {

// `line` must not contain the line terminator (a trailing '\r' is allowed and ignored).
Block parse_line(std::string_view line, std::size_t line_number, const std::string& file);

// The same, into an existing Block whose vectors are reused (no allocation per
// line once they have grown). `block` is completely overwritten.
void parse_line(std::string_view line, std::size_t line_number, const std::string& file,
                Block& block);

// Reads an NC program line by line (LF or CRLF), parses each line and hands
// the Block together with its raw text to the callback. Streaming: memory does
// not grow with the program length.
class BlockReader {
 public:
  BlockReader(std::istream& in, std::string file);
  // Returns false at end of input. Throws abbe::InputError on a bad line.
  bool next(Block& block);
  const std::string& raw_line() const { return line_; }  // without terminator
  // The terminator the current line had in the input: "\n", "\r\n" or "" (last
  // line without one), so that a rewritten program keeps its line endings.
  const char* line_ending() const { return line_ending_; }
  // True if the input began with a UTF-8 byte order mark; it is removed from
  // raw_line() of line 1 (a rewritten program should write it back).
  bool byte_order_mark() const { return byte_order_mark_; }
  const std::string& file() const { return file_; }
  std::size_t line_number() const { return line_number_; }

 private:
  std::istream& in_;
  std::string file_;
  std::string line_;
  std::size_t line_number_ = 0;
  const char* line_ending_ = "";
  bool byte_order_mark_ = false;
};

}  // namespace abbe::gcode
