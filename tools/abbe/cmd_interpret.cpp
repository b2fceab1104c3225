// abbe interpret: parse + interpret only (no fragmenting). Without --canon a
// one-line summary (the interpret-only mode the benchmarks compare with
// rs274); with --canon one line per motion in a canonical form close to
// LinuxCNC's rs274 (used by the interoperability test, docs/interop.md).
#include <fmt/format.h>

#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "abbe/gcode/program.hpp"
#include "abbe/io/atomic_file.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"
#include "command.hpp"
#include "dialect_option.hpp"
#include "input_stream.hpp"
#include "interpreter_options.hpp"
#include "output_options.hpp"

namespace abbe::cli {
namespace {

struct InterpretOptions {
  std::string program;
  bool canon = false;
  std::string output = "-";  // -o: stdout by default
  std::string machine;
  std::optional<double> tool_length;
  std::vector<std::string> tools;           // "H=L"
  std::vector<std::string> tool_diameters;  // "n=D" (G41/G42)
  std::vector<std::string> work_offsets;    // "G55=x,y,z"
  gcode::DialectOptions dialect;
};

gcode::InterpreterConfig make_config(const InterpretOptions& o) {
  gcode::InterpreterConfig config;
  if (!o.machine.empty()) {
    config = pipeline::interpreter_config(machine::Machine::load(o.machine));
  }
  // The tool-tip path does not depend on the length of a G43 tool: a tool
  // without one in the table is accepted (one warning, tool_length unknown).
  config.allow_unknown_tool_length = true;
  config.dialect = o.dialect;
  if (o.tool_length) {
    if (!std::isfinite(*o.tool_length))
      bad_option("--tool-length", "must be a finite number of mm");
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
  return config;
}

const char* plane_name(gcode::Plane plane) {
  switch (plane) {
    case gcode::Plane::xz:
      return "XZ";
    case gcode::Plane::yz:
      return "YZ";
    default:
      return "XY";
  }
}

// One line per motion; coordinates are the tool tip P in machine
// coordinates, mm. ARC_FEED follows rs274's argument order: end and centre in
// the plane's (first, second) axes (XY: X,Y; XZ: Z,X; YZ: Y,Z), rotation,
// then the normal axis' end coordinate.
void append_canon(fmt::memory_buffer& out, const gcode::Motion& m) {
  using gcode::MotionKind;
  fmt::format_to(std::back_inserter(out), "N{} ", m.line);
  switch (m.kind) {
    case MotionKind::rapid:
      fmt::format_to(std::back_inserter(out), "STRAIGHT_TRAVERSE({:.6f}, {:.6f}, {:.6f})",
                     m.end.x(), m.end.y(), m.end.z());
      break;
    case MotionKind::linear:
      fmt::format_to(std::back_inserter(out), "STRAIGHT_FEED({:.6f}, {:.6f}, {:.6f})", m.end.x(),
                     m.end.y(), m.end.z());
      break;
    case MotionKind::arc: {
      int a1 = 0, a2 = 1, n = 2;
      if (m.plane == gcode::Plane::xz) a1 = 2, a2 = 0, n = 1;
      if (m.plane == gcode::Plane::yz) a1 = 1, a2 = 2, n = 0;
      fmt::format_to(std::back_inserter(out),
                     "ARC_FEED({:.6f}, {:.6f}, {:.6f}, {:.6f}, {}, {:.6f})", m.end[a1], m.end[a2],
                     m.center[a1], m.center[a2], m.rotation, m.end[n]);
      fmt::format_to(std::back_inserter(out), " PLANE={}", plane_name(m.plane));
      break;
    }
    case MotionKind::dwell:
      fmt::format_to(std::back_inserter(out), "DWELL({:.6f})", m.dwell_seconds);
      break;
  }
  fmt::format_to(std::back_inserter(out), " F={:.6f} TL={:.6f}\n", m.feed, m.tool_length);
}

int run_interpret(const InterpretOptions& o) {
  const gcode::InterpreterConfig config = make_config(o);
  InputStream input(o.program, "NC program");
  std::istream& in = input.stream();

  std::array<std::size_t, 4> by_kind{};
  io::AtomicOutputFile output(o.output);  // "-": stdout, streamed
  fmt::memory_buffer out;
  auto flush = [&] {
    output.write(out.data(), out.size());
    out.clear();
  };
  gcode::ProgramStats stats;
  try {
    stats = gcode::run_program(in, o.program, config, [&](const gcode::Motion& m) {
      ++by_kind[static_cast<std::size_t>(m.kind)];
      if (o.canon) {
        append_canon(out, m);
        if (out.size() > (1u << 16)) flush();
      }
    });
  } catch (const InputError&) {
    // On stdout the motions made before the bad block are still shown (the
    // interop test checks them against rs274's), then the error is reported;
    // a file is not written.
    if (o.canon && output.is_stdout()) {
      flush();
      std::fflush(stdout);
    }
    throw;
  }
  if (!o.canon)
    fmt::format_to(std::back_inserter(out),
                   "lines={} motions={} rapid={} linear={} arc={} dwell={}\n", stats.lines,
                   stats.motions, by_kind[0], by_kind[1], by_kind[2], by_kind[3]);
  flush();
  output.commit();
  return kOk;
}

const CommandRegistrar registrar(
    "interpret",
    "Parse and interpret an NC program without fragmenting: a summary, or the canonical "
    "motions (--canon)",
    15, [](CLI::App& sub, const GlobalOptions&) -> CommandAction {
      auto o = std::make_shared<InterpretOptions>();
      sub.footer("Example: abbe interpret nc-samples/thesis-toolpath-1.ngc --canon --tool 1=200");
      sub.add_option("program", o->program, "NC program (RS274/LinuxCNC G-code), - for stdin")
          ->required();
      sub.add_flag("--canon", o->canon,
                   "One line per motion (tool tip, machine coordinates, mm): STRAIGHT_TRAVERSE, "
                   "STRAIGHT_FEED, ARC_FEED, DWELL");
      sub.add_option("--machine", o->machine,
                     "Machine file (YAML): tool length, tool table and work offsets");
      sub.add_option("--tool-length", o->tool_length,
                     "Tool length when no G43 is active, mm (overrides the machine file)");
      sub.add_option("--tool", o->tools, "Tool length for G43 Hn as n=L (mm), repeatable");
      sub.add_option("--tool-diameter", o->tool_diameters,
                     "Cutter diameter of tool n for G41/G42 as n=D (mm), repeatable");
      sub.add_option("--work-offset", o->work_offsets,
                     "Work offset as G54..G59=x,y,z (mm, overrides the machine file), repeatable");
      add_output_option(sub, o->output, "the canonical motions or the summary");
      add_dialect_options(sub, o->dialect);
      return [o] { return run_interpret(*o); };
    });

}  // namespace
}  // namespace abbe::cli
