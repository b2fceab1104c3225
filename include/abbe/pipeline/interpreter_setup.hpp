#pragma once
// How a machine file configures the G-code interpreter: work offsets, tool
// table, the tool in the spindle when no G43 is active, and the start of the
// program at machine home (every axis reads 0: s = 0, so the tool tip starts
// at P = −L·e_z).
#include "abbe/gcode/interpreter.hpp"
#include "abbe/machine/machine.hpp"

namespace abbe::pipeline {

gcode::InterpreterConfig interpreter_config(const machine::Machine& machine);

}  // namespace abbe::pipeline
