#pragma once
// Test helper: builds Blocks from simple space-separated text ("G1 X10 Y2")
// without the parser, and runs them through an Interpreter collecting Motions.
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "abbe/gcode/block.hpp"
#include "abbe/gcode/interpreter.hpp"

namespace abbe::gcode::testing {

// Words are a letter and a number, separated by blanks; nothing else.
inline Block make_block(const std::string& text, std::size_t line = 1) {
  Block block;
  block.line = line;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == ' ') {
      ++i;
      continue;
    }
    Word w;
    w.letter = static_cast<char>(std::toupper(static_cast<unsigned char>(text[i])));
    w.begin = static_cast<std::uint32_t>(i);
    ++i;
    w.number_begin = static_cast<std::uint32_t>(i);
    std::size_t j = i;
    while (j < text.size() && text[j] != ' ') ++j;
    const std::string number = text.substr(i, j - i);
    char* endp = nullptr;
    w.value = std::strtod(number.c_str(), &endp);
    if (number.empty() || *endp != '\0') throw std::invalid_argument("bad test word: " + text);
    w.end = static_cast<std::uint32_t>(j);
    block.words.push_back(w);
    i = j;
  }
  return block;
}

// Runs the lines (one block each) and returns every motion made.
inline std::vector<Motion> run_lines(const std::vector<std::string>& lines,
                                     const InterpreterConfig& config = {},
                                     Interpreter* keep = nullptr) {
  Interpreter local(config, "test.nc");
  Interpreter& interp = keep ? *keep : local;
  std::vector<Motion> out;
  std::size_t n = 0;
  for (const auto& text : lines) {
    ++n;
    interp.execute(make_block(text, n), text, [&](const Motion& m) { out.push_back(m); });
  }
  return out;
}

}  // namespace abbe::gcode::testing
