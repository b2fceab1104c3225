#pragma once
// The setup options of every command that reads a program (path, interpret,
// predict, compensate, verify): --tool-length L, --tool H=L, --work-offset
// G55=x,y,z override the machine file's tool length, tool table and work
// offsets (without a machine file: the defaults, zero). Bad values are
// InputErrors naming the option.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "abbe/gcode/interpreter.hpp"

namespace abbe::cli {

struct SetupOptions {
  std::optional<double> tool_length;
  std::vector<std::string> tools;           // "H=L"
  std::vector<std::string> tool_diameters;  // "n=D" (G41/G42)
  std::vector<std::string> work_offsets;  // "G55=x,y,z"
};

void add_setup_options(CLI::App& sub, SetupOptions& o);

// Applies the options to a configuration (the program starts with the
// spindle where the configuration puts it: a new tool length moves the
// start tip by the change of length).
void apply_setup_options(const SetupOptions& o, gcode::InterpreterConfig& config);

}  // namespace abbe::cli
