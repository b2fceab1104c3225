// abbe diagnose: where the machine's error model is wrong on measured data,
// which catalogued effect explains it, the extended model (overlay) and its
// held-out gain (docs/diagnosis.md).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "abbe/diagnose/diagnosis.hpp"
#include "abbe/io/atomic_file.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/io/measured_data.hpp"
#include "abbe/machine/machine.hpp"
#include "command.hpp"
#include "output_options.hpp"
#include "progress.hpp"
#include "table_uncertainty_option.hpp"

namespace abbe::cli {
namespace {

struct DiagnoseCliOptions {
  std::string machine;
  std::string measured;
  std::string model = "ae-arm";
  std::string out;
  std::string overlay;
  std::string extend;
  int folds = 5;
  std::uint64_t seed = 1;
  double max_period = 100.0;
  bool infer_directions = false;
  long table_draws = -1;  // --table-uncertainty; -1: not given
};

int run_diagnose(const DiagnoseCliOptions& o, const GlobalOptions& g) {
  const machine::Machine machine = machine::Machine::load(o.machine);
  diagnose::DiagnoseOptions opt;
  // Progress on a terminal, in steps: reading the data, the residuals and
  // candidates, then each step of the effect selection (it may end early).
  const int steps = 2 + opt.selection.max_terms;
  Progress progress("diagnose", static_cast<std::uint64_t>(steps), !g.quiet, "steps");
  progress.update(0);
  const io::MeasuredData data = io::load_measured_data(o.measured);
  progress.update(1);
  auto kind = model::parse_model_kind(o.model);
  if (!kind)
    throw InputError(
        {"<command line>", 0, 0, "--model", ""},
        fmt::format("unknown model \"{}\" ({})", o.model, model::model_names_text(false)));
  opt.model = *kind;
  opt.selection.folds = o.folds;
  opt.selection.seed = o.seed;
  opt.candidates.max_period_mm = o.max_period;
  opt.infer_directions = o.infer_directions;
  opt.tables = table_uncertainty_options(o.table_draws, o.seed);
  std::optional<diagnose::Overlay> extend;
  if (!o.extend.empty()) {
    extend = diagnose::Overlay::load(o.extend);
    opt.extend = &*extend;
  }
  if (progress.active())
    opt.selection.on_step = [&](int step) {
      progress.update(static_cast<std::uint64_t>(2 + step));
    };
  const diagnose::Diagnosis d = diagnose::diagnose(machine, data, opt);
  progress.finish();
  for (const std::string& w : d.extend_check.warnings) spdlog::warn("{}", w);
  if (const std::string w = diagnose::travel_warning(d); !w.empty()) spdlog::warn("{}", w);
  if (!o.out.empty()) io::write_file_atomically(o.out, diagnose::report_json(d));
  if (!o.overlay.empty())
    io::write_file_atomically(o.overlay, diagnose::make_overlay(d, opt.extend).to_yaml());
  if (!g.quiet) {
    std::string text = diagnose::report_text(d);
    if (g.verbose > 0)
      for (const auto& l : d.log) text += "  " + l + "\n";
    const bool json_on_stdout = o.out == "-";
    std::fputs(text.c_str(), json_on_stdout ? stderr : stdout);
  }
  return kOk;
}

const CommandRegistrar registrar(
    "diagnose",
    "Find where the error model is wrong on measured data, name the cause, extend the model", 70,
    [](CLI::App& sub, const GlobalOptions& g) -> CommandAction {
      auto o = std::make_shared<DiagnoseCliOptions>();
      sub.footer(
          "Example: abbe diagnose --machine machines/sample/machine.yaml "
          "--measured machines/sample/measured-grid.csv -o diagnosis.json");
      sub.add_option("--machine", o->machine, "Machine file (YAML, docs/formats.md)")->required();
      sub.add_option("--measured", o->measured, "Measured data (CSV, docs/formats.md; - for stdin)")
          ->required();
      sub.add_option("--model", o->model,
                     "Error model diagnosed: " + model::model_names_text(false))
          ->check(CLI::IsMember(model::model_names(false)))
          ->capture_default_str();
      add_output_option(sub, o->out, "Write the JSON report to FILE");
      add_hidden_alias(sub, "--out", o->out);
      sub.add_option("--overlay", o->overlay, "Write the extended model (overlay YAML) to FILE");
      sub.add_option("--extend", o->extend,
                     "Add an earlier overlay to the model first, and say what it does on these "
                     "data (RMS after their own datum without and with it; warnings outside its "
                     "domain)");
      sub.add_option("--folds", o->folds, "Folds of the held-out check")
          ->check(CLI::Range(2, 50))
          ->capture_default_str();
      sub.add_option("--seed", o->seed,
                     "Seed of the fold assignment (and of the draws of --table-uncertainty)")
          ->capture_default_str();
      add_table_uncertainty_option(sub, o->table_draws);
      sub.add_option("--max-period", o->max_period, "Longest cyclic period searched, mm")
          ->check(CLI::Range(8.0, 10000.0))
          ->capture_default_str();
      sub.add_flag("--infer-directions", o->infer_directions,
                   "Where the data have no vx/vy/vz for an axis, take its approach direction from "
                   "the order of the points (per set, by time): the sign of its last move "
                   "between consecutive points. Only for points reached one from the other (a "
                   "grid or a line walked point to point), not for probing cycles");
      const GlobalOptions* gp = &g;
      return [o, gp] { return run_diagnose(*o, *gp); };
    });

}  // namespace
}  // namespace abbe::cli
