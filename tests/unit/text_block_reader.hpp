#pragma once
// Test helper: a BlockReader reading a string, with the Block it fills.
#include <sstream>
#include <string>

#include "abbe/gcode/parser.hpp"

namespace abbe::gcode::testing {

struct TextBlockReader {
  TextBlockReader(const std::string& text, const std::string& file) : in(text), reader(in, file) {}
  // The next block into `block`; false at the end of the text.
  bool next() { return reader.next(block); }

  std::istringstream in;
  BlockReader reader;
  Block block;
};

}  // namespace abbe::gcode::testing
