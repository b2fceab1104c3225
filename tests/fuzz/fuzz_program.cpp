// libFuzzer target: any bytes as an NC program. The only acceptable failure is
// abbe::InputError; anything else (a crash, a sanitizer report, another
// exception) is a bug. On the way, every line the parser accepts is checked
// against the offset contract the post-processor relies on; the program then
// goes through the fragmenter (abbe path) and compensate_program — with
// all-zero tables the compensated program must be the input byte for byte,
// with the sample machine it must keep at least every line of the input.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <string_view>

#include "abbe/compensate/program_compensator.hpp"
#include "abbe/gcode/parser.hpp"
#include "abbe/gcode/program.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"
#include "abbe/pipeline/program_path.hpp"

namespace {

constexpr std::size_t kMotionBudget = 200'000;
constexpr std::size_t kPointBudget = 1'000'000;
struct OverBudget {};

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

struct Machines {
  abbe::machine::Machine zero =
      abbe::machine::Machine::load(ABBE_SOURCE_DIR "/tests/data/compensate/zero.yaml");
  abbe::machine::Machine sample =
      abbe::machine::Machine::load(ABBE_SOURCE_DIR "/machines/sample/machine.yaml");
  abbe::model::ErrorModel zero_model{zero, abbe::model::ModelKind::ae_arm};
  abbe::model::ErrorModel sample_model{sample, abbe::model::ModelKind::ae_arm};
};

const Machines& machines() {
  static const Machines m;
  return m;
}

abbe::gcode::InterpreterConfig config_of(const abbe::machine::Machine& m) {
  abbe::gcode::InterpreterConfig c = abbe::pipeline::interpreter_config(m);
  c.dialect.loop_limit = 10'000;
  return c;
}

// compensate_program's output, or nothing when it refuses the program.
bool compensated(const std::string& text, const abbe::machine::Machine& m,
                 const abbe::model::ErrorModel& model, std::string& out) {
  std::istringstream in(text);
  try {
    abbe::compensate::compensate_program(in, "fuzz.nc", config_of(m), model, {},
                                         [&](const char* d, std::size_t n) { out.append(d, n); });
    return true;
  } catch (const abbe::InputError&) {
    return false;
  }
}

std::size_t count_lines(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
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
  // Programs that expand into more motions or path points than the budgets
  // below (a canned cycle with L 70000 inside a loop, a 10 km move) are
  // valid but slow; the input is dropped there, as the loop limit does.
  std::istringstream in(text);
  abbe::gcode::InterpreterConfig config;
  config.dialect.loop_limit = 10'000;
  std::size_t motions = 0;
  try {
    abbe::gcode::run_program(in, "fuzz.nc", config, [&](const abbe::gcode::Motion&) {
      if (++motions > kMotionBudget) throw OverBudget{};
    });
  } catch (const abbe::InputError&) {
    return 0;  // compensate would refuse it at the same line
  } catch (const OverBudget&) {
    return 0;
  }

  // Through the fragmenter, as `abbe path` with the sample machine.
  const Machines& m = machines();
  std::size_t points = 0;
  try {
    std::istringstream again(text);
    abbe::pipeline::run_path(again, "fuzz.nc", config_of(m.sample), abbe::pipeline::PathOptions{},
                             [&](const abbe::path::PathPoint&) {
                               if (++points > kPointBudget) throw OverBudget{};
                             });
  } catch (const abbe::InputError&) {
  } catch (const OverBudget&) {
    return 0;
  }

  // compensate_program: all-zero tables change nothing; the sample machine
  // keeps every line (inserted pieces only add lines).
  std::string out;
  if (compensated(text, m.zero, m.zero_model, out)) check(out == text);
  out.clear();
  if (compensated(text, m.sample, m.sample_model, out))
    check(count_lines(out) >= count_lines(text));
  return 0;
}
