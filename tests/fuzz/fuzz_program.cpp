// libFuzzer target: any bytes as an NC program. The only acceptable failure is
// abbe::InputError; anything else (a crash, a sanitizer report, another
// exception) is a bug. On the way, every line the parser accepts is checked
// against the offset contract the post-processor relies on.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <string_view>

#include "abbe/gcode/parser.hpp"
#include "abbe/gcode/program.hpp"
#include "abbe/io/input_error.hpp"

namespace {

void check(bool ok) {
  if (!ok) __builtin_trap();
}

// For an accepted line: every word's spans lie inside the line, in order, the
// letter is the word's letter and the number text parses to the same value.
void check_offsets(std::string_view line, const abbe::gcode::Block& block) {
  std::string_view text = line;
  if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
  std::uint32_t previous_end = 0;
  for (const auto& w : block.words) {
    check(previous_end <= w.begin && w.begin < w.number_begin && w.number_begin < w.end &&
          w.end <= text.size());
    const char letter = text[w.begin];
    check(letter == w.letter || letter - 'a' + 'A' == w.letter);
    const std::string alone =
        "X" + std::string(text.substr(w.number_begin, w.end - w.number_begin));
    const auto again = abbe::gcode::parse_line(alone, 1, "fuzz");
    check(again.words.size() == 1 && again.words[0].value == w.value);
    previous_end = w.end;
  }
  for (const auto& c : block.comments) check(c.begin < c.end && c.end <= text.size());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);

  // The parser alone, line by line.
  std::size_t begin = 0;
  std::size_t line_number = 1;
  while (begin <= text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    const std::string_view line(text.data() + begin, end - begin);
    try {
      check_offsets(line, abbe::gcode::parse_line(line, line_number, "fuzz.nc"));
    } catch (const abbe::InputError& e) {
      check(e.where().line == line_number && e.where().column >= 1 &&
            e.where().column <= line.size() + 1);
    }
    begin = end + 1;
    ++line_number;
  }

  // The whole front end: parser, control flow and interpreter. Loops are
  // bounded by a small limit so that an input spends its time on variety,
  // not on one long loop (the limit itself is what a hang would defeat).
  std::istringstream in(text);
  abbe::gcode::InterpreterConfig config;
  config.dialect.loop_limit = 10'000;
  try {
    abbe::gcode::run_program(in, "fuzz.nc", config, [](const abbe::gcode::Motion&) {});
  } catch (const abbe::InputError&) {
  }
  return 0;
}
