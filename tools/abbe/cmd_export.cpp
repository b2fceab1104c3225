// abbe export: the machine's predicted errors as tables for its control
// (docs/export.md) — LinuxCNC per-joint compensation files, or a volumetric
// grid (CSV) for a volumetric compensation component.
#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "abbe/compensate/controller_tables.hpp"
#include "abbe/diagnose/overlay_extension.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/model_kind.hpp"
#include "command.hpp"
#include "model_option.hpp"

namespace abbe::cli {
namespace {

struct ExportOptions {
  std::string machine;
  std::string model = "ae-arm";
  std::string extend;
  std::string output;
  std::optional<double> tool_length;  // default: the machine's
  std::vector<double> at;             // linuxcnc: tool tip X,Y,Z (default: the travel's centre)
  std::vector<double> step;           // one value or X,Y,Z
  std::vector<std::size_t> count;     // grid: one value or X,Y,Z
  std::string units = "mm";           // linuxcnc: the files' unit
};

[[noreturn]] void bad_option(const std::string& option, const std::string& message) {
  throw InputError({"<command line>", 0, 0, option, ""}, message);
}

std::shared_ptr<const model::ErrorExtension> extension_of(const ExportOptions& o,
                                                          const machine::Machine& machine) {
  if (o.extend.empty()) return nullptr;
  return std::make_shared<const diagnose::OverlayExtension>(diagnose::Overlay::load(o.extend),
                                                            machine);
}

double tool_length_of(const ExportOptions& o, const machine::Machine& machine) {
  const double l = o.tool_length ? *o.tool_length : machine.tool_length();
  if (!(l >= 0.0 && l < 1e4))
    bad_option("--tool-length", fmt::format("{} mm: not a tool length", l));
  return l;
}

int run_linuxcnc(const ExportOptions& o) {
  const machine::Machine machine = machine::Machine::load(o.machine);
  compensate::JointTableOptions jo;
  const std::vector<model::ModelKind> kinds = model::parse_model_list(o.model);
  if (kinds.size() != 1) bad_option("--model", "a LinuxCNC table holds one model");
  jo.model = kinds[0];
  jo.extension = extension_of(o, machine);
  jo.tool_length = tool_length_of(o, machine);
  jo.at_tip = o.at.empty() ? compensate::travel_centre_tip(machine, jo.tool_length)
                           : Eigen::Vector3d(o.at[0], o.at[1], o.at[2]);
  if (o.step.size() > 1) bad_option("--step", "one step for every joint");
  jo.step = o.step.empty() ? 0.0 : o.step[0];
  jo.inch = o.units == "inch";
  if (!o.step.empty() && !(jo.step > 0.0)) bad_option("--step", "the step must be > 0 mm");
  std::fputs(compensate::export_linuxcnc(machine, jo, o.output).c_str(), stdout);
  warn_overlay_domain(jo.extension.get());
  return kOk;
}

int run_grid(const ExportOptions& o) {
  const machine::Machine machine = machine::Machine::load(o.machine);
  compensate::GridOptions go;
  go.models = model::parse_model_list(o.model);
  go.extension = extension_of(o, machine);
  go.tool_length = tool_length_of(o, machine);
  if (!o.step.empty() && !o.count.empty())
    bad_option("--count", "give --step or --count, not both");
  if (o.step.size() == 1) go.step.setConstant(o.step[0]);
  if (o.step.size() == 3) go.step = Eigen::Vector3d(o.step[0], o.step[1], o.step[2]);
  if (o.step.size() == 2) bad_option("--step", "one value or three (X,Y,Z)");
  for (std::size_t a = 0; a < 3; ++a)
    if (!o.count.empty()) go.count[a] = o.count.size() == 1 ? o.count[0] : o.count.at(a);
  if (o.count.size() == 2) bad_option("--count", "one value or three (X,Y,Z)");
  for (std::size_t n : go.count)
    if (!o.count.empty() && n < 2) bad_option("--count", "at least 2 nodes per axis");
  const std::string summary = compensate::export_grid(machine, go, o.output);
  warn_overlay_domain(go.extension.get(), go.models.size());
  std::fputs(summary.c_str(), o.output == "-" ? stderr : stdout);
  return kOk;
}

void add_common(CLI::App& sub, ExportOptions& o, bool all_models) {
  sub.add_option("--machine", o.machine, "Machine file (YAML, docs/formats.md)")->required();
  sub.add_option("--model", o.model, "Error model: " + model::model_names_text(all_models))
      ->check(CLI::IsMember(model::model_names(all_models)))
      ->capture_default_str();
  sub.add_option("--extend", o.extend,
                 "Add the effects of an overlay written by `abbe diagnose --overlay`");
  sub.add_option("--tool-length", o.tool_length,
                 "Tool length L, mm (default: the machine file's tool_length)");
}

const CommandRegistrar registrar(
    "export",
    "Write the machine's predicted errors as controller tables: LinuxCNC per-joint "
    "compensation files or a volumetric grid (docs/export.md)",
    45, [](CLI::App& sub, const GlobalOptions&) -> CommandAction {
      sub.require_subcommand(1);
      auto lo = std::make_shared<ExportOptions>();
      CLI::App* lin = sub.add_subcommand(
          "linuxcnc",
          "Per-joint COMP_FILE tables (COMP_FILE_TYPE 1): DIR/x.comp, y.comp, z.comp and "
          "DIR/linuxcnc.ini with the lines that load them");
      lin->footer(
          "Example: abbe export linuxcnc --machine machines/sample/machine.yaml "
          "--at -495,-250,-410 --tool-length 130 -o comp");
      add_common(*lin, *lo, false);
      lin->add_option("--at", lo->at,
                      "Tool tip X,Y,Z (mm, machine coordinates) where the other axes stand while "
                      "one moves (default: the centre of the travel)")
          ->delimiter(',')
          ->expected(3);
      lin->add_option("--step", lo->step,
                      "Largest distance between entries, mm (default 5, wider when the travel "
                      "needs more than 256 entries)")
          ->expected(1);
      lin->add_option("--units", lo->units,
                      "Unit of the files, as LinuxCNC's [TRAJ] LINEAR_UNITS (positions and trims)")
          ->check(CLI::IsMember({"mm", "inch"}))
          ->capture_default_str();
      lin->add_option("-o,--output", lo->output, "Output directory (created if missing)")
          ->required();

      auto go = std::make_shared<ExportOptions>();
      CLI::App* grid = sub.add_subcommand(
          "grid", "Volumetric grid: x,y,z → dx,dy,dz (µm) on a regular grid over the travel (CSV)");
      grid->footer(
          "Example: abbe export grid --machine machines/sample/machine.yaml --model all "
          "--step 50 -o grid.csv");
      add_common(*grid, *go, true);
      grid->add_option("--step", go->step,
                       "Largest node spacing, mm: one value or X,Y,Z (default 25)")
          ->delimiter(',')
          ->expected(1, 3);
      grid->add_option("--count", go->count,
                       "Nodes per axis: one value or X,Y,Z (instead of --step)")
          ->delimiter(',')
          ->expected(1, 3);
      grid->add_option("-o,--output", go->output, "Output CSV (written atomically), - for stdout")
          ->required();
      return [lo, go, lin, grid]() -> int {
        if (lin->parsed()) return run_linuxcnc(*lo);
        if (grid->parsed()) return run_grid(*go);
        return kUsage;
      };
    });

}  // namespace
}  // namespace abbe::cli
