#pragma once
// Line-by-line G-code parser (Boost.Spirit X3, grammar in grammar/).
// parse_line() turns one line into a Block or throws abbe::InputError naming
// file, line and column. Constructs abbe does not support (#parameters,
// [expressions], O-word control flow) are refused here with their name.
#include <cstddef>
#include <istream>
#include <memory>
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

// Reads an NC program line by line (LF or CRLF) and parses each line.
// Streaming: the input is read in chunks of 1 MiB (more only for a longer
// line), so memory does not grow with the program length. A line of 16 MiB
// or more is an InputError (a file without line ends is not buffered
// without limit). The stream is read
// ahead of the line returned last.
class BlockReader {
 public:
  BlockReader(std::istream& in, std::string file);
  ~BlockReader();
  BlockReader(BlockReader&&) noexcept;
  // Returns false at end of input. Throws abbe::InputError on a bad line.
  bool next(Block& block);
  // The current line without its terminator (and without a byte order mark).
  const std::string& raw_line() const;
  // The same text without a copy; valid until the next call of next().
  std::string_view line_text() const { return line_view_; }
  // The terminator the current line had in the input: "\n", "\r\n" or "" (last
  // line without one), so that a rewritten program keeps its line endings.
  const char* line_ending() const { return line_ending_; }
  // True if the input began with a UTF-8 byte order mark; it is removed from
  // raw_line() of line 1 (a rewritten program should write it back).
  bool byte_order_mark() const { return byte_order_mark_; }
  const std::string& file() const { return file_; }
  std::size_t line_number() const { return line_number_; }

 private:
  bool next_line();  // into line_view_ and line_ending_; false at end of input
  void refill();     // reads the next chunk after the unfinished line

  std::istream& in_;
  std::unique_ptr<char[]> buffer_;
  std::size_t capacity_ = 0;
  std::size_t begin_ = 0;    // first byte not yet returned
  std::size_t end_ = 0;      // one past the last byte read
  bool at_end_ = false;      // the stream has nothing more
  bool read_error_ = false;  // ... because reading failed
  std::string file_;
  std::string_view line_view_;  // the current line, in buffer_
  mutable std::string line_;    // its copy, made by raw_line()
  mutable bool line_copied_ = false;
  std::size_t line_number_ = 0;
  const char* line_ending_ = "";
  bool byte_order_mark_ = false;
};

}  // namespace abbe::gcode
