#pragma once
// --dialect and --integers: how an NC program is written, for every command
// that reads one (path, interpret, predict, report predict, compensate,
// verify, simulate measure).
#include <CLI/CLI.hpp>

#include "abbe/gcode/dialect.hpp"

namespace abbe::cli {

void add_dialect_options(CLI::App& sub, gcode::DialectOptions& dialect);

}  // namespace abbe::cli
