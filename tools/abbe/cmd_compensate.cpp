// abbe compensate: writes the NC program with corrected coordinates so that
// the predicted path is the nominal one (docs/compensation.md). Streams block
// by block into a temporary file renamed over the output at the end.
#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include "abbe/compensate/program_compensator.hpp"
#include "abbe/compensate/provenance.hpp"
#include "abbe/io/atomic_file.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/pipeline/aligned_prediction.hpp"
#include "abbe/pipeline/alignment_extension.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"
#include "align_options.hpp"
#include "command.hpp"
#include "dialect_option.hpp"
#include "input_stream.hpp"
#include "model_option.hpp"
#include "progress.hpp"
#include "setup_options.hpp"

namespace abbe::cli {
namespace {

struct CompensateCliOptions {
  std::string input;
  ModelOptions m;
  std::string output;
  compensate::CompensateOptions c;
  bool in_place = false;
  bool allow_unconverged = false;
  gcode::DialectOptions dialect;
  AlignCliOptions align;  // correct only what the part's set-up leaves
  SetupOptions setup;
};

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (std::filesystem::equivalent(a, b, ec)) return true;
  return std::filesystem::weakly_canonical(a, ec) == std::filesystem::weakly_canonical(b, ec);
}

// --align best-fit|datums: the model predicts what remains after the part's
// set-up (pipeline/alignment_extension.hpp); returns the line the summary
// reports.
std::string align_model(const CompensateCliOptions& o, const pipeline::AlignOptions& ao,
                        const machine::Machine& machine, model::ErrorModel& model) {
  if (!o.m.extend.empty())
    throw InputError({"<command line>", 0, 0, "--align", ""},
                     "--align with --extend is not supported yet");
  std::ifstream first(o.input, std::ios::binary);
  if (!first)
    throw InputError({o.input, 0, 0, "", ""},
                     std::string("cannot open the input: ") + std::strerror(errno));
  pipeline::PathOptions path;
  path.dialect = o.dialect;
  const pipeline::ModelAlignment a =
      pipeline::program_setup(first, o.input, machine, model.kind(), path, ao);
  model = model.with_extension(std::make_shared<const pipeline::AlignmentExtension>(a.motion));
  return fmt::format(
      "  --align {}: the set-up takes out a rotation ({:.3f}, {:.3f}, {:.3f}) µrad and a shift "
      "({:.4f}, {:.4f}, {:.4f}) µm of the part's centroid; predicted part max |e| {:.4f} µm, "
      "{:.4f} µm after the set-up (corrected)\n",
      o.align.align, a.rotation_urad.x(), a.rotation_urad.y(), a.rotation_urad.z(),
      a.centroid_shift_um.x(), a.centroid_shift_um.y(), a.centroid_shift_um.z(), a.absolute.max_um,
      a.aligned.max_um);
}

int run_compensate(CompensateCliOptions o, const GlobalOptions& g) {
  if (o.output.empty() && !o.in_place)
    throw InputError({"<command line>", 0, 0, "-o", ""},
                     "no output: give -o OUT.nc (or --in-place to replace the input)");
  if (o.in_place) {
    if (!o.output.empty() && !same_file(o.output, o.input))
      throw InputError({"<command line>", 0, 0, "--in-place", ""},
                       "--in-place and -o name different files");
    o.output = o.input;
  } else if (o.output != "-" && same_file(o.output, o.input)) {
    throw InputError({"<command line>", 0, 0, "-o", ""},
                     "the output is the input: give --in-place to replace it");
  }
  pipeline::AlignOptions ao;
  if (!align_options(o.align, "compensate", ao)) return kUsage;
  const machine::Machine machine = machine::Machine::load(o.m.machine);
  model::ErrorModel model = make_model(o.m, machine);
  const std::string setup_text =
      ao.method == pipeline::AlignMethod::none ? "" : align_model(o, ao, machine, model);
  gcode::InterpreterConfig config = pipeline::interpreter_config(machine);
  config.dialect = o.dialect;
  apply_setup_options(o.setup, config);
  o.c.travel = machine.spec().travel;
  o.c.provenance = compensate::make_provenance(ABBE_VERSION, machine, config, o.m.model, o.m.extend,
                                               o.m.extend_time, o.c);

  if (o.in_place && o.input == "-")
    throw InputError({"<command line>", 0, 0, "--in-place", ""},
                     "--in-place needs a file, not - (standard input)");
  InputStream input(o.input, "the input");
  std::istream& in = input.stream();
  io::AtomicOutputFile out(o.output);
  // Progress on a terminal: bytes of the program read.
  Progress progress("compensate", Progress::file_size(o.input), !g.quiet);
  std::uint64_t bytes_read = 0;
  ProgressStreambuf counted(in.rdbuf(), progress, bytes_read);
  std::istream program(&counted);
  const compensate::CompensateSummary s = compensate::compensate_program(
      program, o.input, config, model, o.c, [&](const char* d, std::size_t n) { out.write(d, n); });
  progress.finish();
  warn_overlay_domain(model.extension());

  std::string text = fmt::format(
      "{}: {} lines, {} blocks changed, {} pieces inserted, {} points, max correction {:.4f} µm, "
      "{} out of range ({}), {} unconverged\n",
      o.input, s.lines, s.blocks_changed, s.pieces_inserted, s.points, s.max_correction_um,
      s.out_of_range_points, machine::to_string(machine.out_of_range()), s.unconverged_points);
  text += setup_text;
  if (s.arcs_split_turns)
    text += fmt::format("  {} multi-turn arcs split into pieces (P word removed)\n",
                        s.arcs_split_turns);
  text += compensate::segment_text(s);
  if (!s.travel_text.empty())
    text += fmt::format("  warning: {} (--allow-outside-travel)\n", s.travel_text);
  if (s.uncompensated_blocks)
    text += fmt::format("  {} canned-cycle blocks left uncompensated\n", s.uncompensated_blocks);
  for (const auto& w : s.warnings) text += "  warning: " + w + "\n";
  if (s.unconverged_points) {
    std::string lines;
    for (auto l : s.unconverged_lines) lines += fmt::format("{}{}", lines.empty() ? "" : ", ", l);
    text += fmt::format("  unconverged points on lines {}\n", lines);
    if (!o.allow_unconverged) {
      std::fputs(text.c_str(), stderr);
      throw InputError(
          {o.input, s.unconverged_lines.front(), 0, "", ""},
          fmt::format("{} points did not converge to {} µm in {} iterations; no "
                      "output written (--allow-unconverged writes it anyway)",
                      s.unconverged_points, o.c.solver.tolerance_um, o.c.solver.max_iterations));
    }
  }
  out.commit();
  std::fputs(text.c_str(), o.output == "-" ? stderr : stdout);
  return kOk;
}

const CommandRegistrar registrar(
    "compensate", "Write the NC program with coordinates corrected for the predicted errors", 40,
    [](CLI::App& sub, const GlobalOptions& g) -> CommandAction {
      auto o = std::make_shared<CompensateCliOptions>();
      sub.footer(
          "Example: abbe compensate nc-samples/thesis-toolpath-1.ngc --machine "
          "machines/sample/machine.yaml --tol 1 -o compensated.ngc");
      sub.add_option("input", o->input, "NC program (- for stdin)")->required();
      sub.add_option("-o,--output", o->output, "Output program (written atomically), - for stdout");
      add_dialect_options(sub, o->dialect);
      add_setup_options(sub, o->setup);
      add_model_options(sub, o->m,
                        "Compensate the extended model: add the effects of an overlay written by "
                        "`abbe diagnose --overlay`");
      sub.add_option("--tol", o->c.tol_um,
                     "Allowed predicted deviation from the nominal path, µm (splits moves)")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
      sub.add_option("--step", o->c.step, "Fragment step, mm")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
      sub.add_option("--min-segment", o->c.min_segment,
                     "No inserted piece shorter than this, mm; a reversal jump below it and "
                     "within --tol is taken up along the move instead of by a micro move of "
                     "its own (0: micro moves for every jump)")
          ->check(CLI::Range(0.0, 1.0))
          ->capture_default_str();
      sub.add_flag("--spread-takeups", o->c.spread_takeups,
                   "Take up every reversal jump below --min-segment along the move, also those "
                   "beyond --tol: no move shorter than --min-segment, but the path leaves the "
                   "nominal by up to the jump just after such reversals (verify shows it)");
      sub.add_option("--decimals", o->c.decimals,
                     "Decimal places of corrected numbers (default 4 in mm, 5 in inch programs; "
                     "never fewer than the number had)")
          ->check(CLI::Range(0, 9));
      sub.add_flag("--renumber", o->c.renumber, "Give inserted pieces N numbers");
      sub.add_flag("--allow-outside-travel", o->c.allow_outside_travel,
                   "Compensate points outside the machine's travel (counted) instead of refusing "
                   "the program");
      sub.add_flag("--in-place", o->in_place, "Replace the input (atomically)");
      add_align_options(sub, o->align,
                        "Correct only what remains after the part's set-up: best-fit (a best fit "
                        "of the predicted part over the cutting points) or datums (3-2-1, "
                        "--datum-*)");
      sub.add_flag("--allow-unconverged", o->allow_unconverged,
                   "Write the output even if some points did not converge");
      const GlobalOptions* gp = &g;
      return [o, gp] { return run_compensate(*o, *gp); };
    });

}  // namespace
}  // namespace abbe::cli
