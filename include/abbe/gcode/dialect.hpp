#pragma once
// Which controller's G-code a program is written for. abbe's interpreter
// speaks LinuxCNC's RS274/NGC; a Fanuc/Haas-style program is read through an
// adapter (src/gcode/fanuc_dialect.cpp) that turns each block into its
// RS274/NGC equivalent, and through a runner that follows M98/M99
// subprogram calls between the O-numbered programs of one file.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "abbe/gcode/block.hpp"

namespace abbe::gcode {

enum class Dialect : std::uint8_t {
  linuxcnc,  // RS274/NGC as LinuxCNC 2.9's rs274ngc reads it (the default)
  fanuc,     // Fanuc 0i/30i and Haas style, as CAM posts write it
};

// Fanuc: how a number written without a decimal point is read in a word
// that is a length (X Y Z I J K R Q). Fanuc's default ("X100" is 100 least
// input increments: 0.1 mm, or 0.01 inch) or the "calculator-type" input of
// parameter DPI (3401#0), where "X100" is 100 mm (or inch).
enum class IntegerNumbers : std::uint8_t {
  least_increment,  // 0.001 mm / 0.0001 inch (increment system IS-B)
  whole_units,      // calculator-type decimal point input
};

struct DialectOptions {
  Dialect dialect = Dialect::linuxcnc;
  IntegerNumbers integers = IntegerNumbers::least_increment;
  // LinuxCNC dialect, parameters and O-words (src/gcode/program_runner.cpp):
  std::string var_file;         // rs274's parameter file ("number value" lines), read at start
  std::string subroutine_path;  // folder of name.ngc files holding "o<name> sub" (o<name> call)
  // Loop iterations (while, do, repeat, all loops together) before a program
  // is refused as a runaway loop.
  std::uint64_t loop_limit = 10'000'000;
};

// The M98 (subprogram call) or M99 (return) word of a Fanuc block, if any:
// its lines run once per call, which a line-by-line post-processor cannot
// follow.
const Word* subprogram_flow_word(const Block& block);

// "linuxcnc" / "fanuc"; empty for an unknown name.
std::optional<Dialect> dialect_from_name(std::string_view name);
const char* dialect_name(Dialect dialect);
// "increment" / "units".
std::optional<IntegerNumbers> integer_numbers_from_name(std::string_view name);

}  // namespace abbe::gcode
