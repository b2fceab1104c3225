#include "setup_options.hpp"

#include <cmath>

#include "interpreter_options.hpp"

namespace abbe::cli {

void add_setup_options(CLI::App& sub, SetupOptions& o) {
  sub.add_option("--tool-length", o.tool_length,
                 "Tool length when no G43 is active, mm (overrides the machine file)");
  sub.add_option("--tool", o.tools,
                 "Tool length for G43 Hn as n=L (mm, overrides the machine file), repeatable");
  sub.add_option("--tool-diameter", o.tool_diameters,
                 "Cutter diameter of tool n for G41/G42 as n=D (mm), repeatable");
  sub.add_option("--work-offset", o.work_offsets,
                 "Work offset as G54..G59=x,y,z (mm, overrides the machine file), repeatable");
}

void apply_setup_options(const SetupOptions& o, gcode::InterpreterConfig& config) {
  if (o.tool_length) {
    if (!std::isfinite(*o.tool_length) || *o.tool_length < 0.0)
      bad_option("--tool-length", "must be a finite, non-negative number of mm");
    config.initial_position.z() += config.default_tool_length - *o.tool_length;
    config.default_tool_length = *o.tool_length;
  }
  for (const auto& t : o.tools) {
    const auto [h, length] = parse_tool_option(t);
    config.tool_lengths[h] = length;
  }
  for (const auto& t : o.tool_diameters) {
    const auto [n, diameter] = parse_tool_diameter_option(t);
    config.tool_diameters[n] = diameter;
  }
  for (const auto& w : o.work_offsets) {
    const auto [index, offset] = parse_work_offset_option(w);
    config.work_offsets[index] = offset;
  }
}

}  // namespace abbe::cli
