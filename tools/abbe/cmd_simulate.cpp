// abbe simulate: the virtual machine — generate a ground truth and its laser
// campaign (machine), re-run a campaign (campaign), or measure the truth
// with injected effects (measure). See docs/virtual-machine.md.
#include <spdlog/spdlog.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "abbe/gcode/program.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/machine/travel_check.hpp"
#include "abbe/pipeline/program_path.hpp"
#include "abbe/sim/laser_campaign.hpp"
#include "abbe/sim/real_conventions.hpp"
#include "abbe/sim/text_file.hpp"
#include "abbe/sim/truth_file.hpp"
#include "abbe/sim/validation_measurement.hpp"
#include "box_option.hpp"
#include "command.hpp"
#include "dialect_option.hpp"
#include "input_stream.hpp"

namespace abbe::cli {
namespace {

[[noreturn]] void bad_option(const std::string& field, const std::string& message) {
  SourceLocation where;
  where.file = "<command line>";
  where.field = field;
  throw InputError(where, message);
}

std::vector<sim::Effect> parse_effects(const std::vector<std::string>& specs) {
  std::vector<sim::Effect> effects;
  for (const std::string& s : specs) {
    try {
      effects.push_back(sim::parse_effect(s));
    } catch (const std::invalid_argument& e) {
      bad_option("--inject", e.what());
    }
  }
  return effects;
}

// A finite number ≥ 0 with an optional unit suffix ("0.5um", "0.5"); NaN if it is not one.
double parse_non_negative(const std::string& text, const std::string& unit) {
  std::string number = text;
  if (number.size() > unit.size() &&
      number.compare(number.size() - unit.size(), unit.size(), unit) == 0)
    number.resize(number.size() - unit.size());
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(number.c_str(), &end);
  if (number.empty() || end != number.c_str() + number.size() || errno != 0 || !std::isfinite(v) ||
      v < 0.0)
    return NAN;
  return v;
}

// "0.5µm", "0.5um" (the ASCII spelling of the same), "0.5" (µm) → µm.
double parse_um(const std::string& field, const std::string& text) {
  double v = parse_non_negative(text, "µm");
  if (std::isnan(v)) v = parse_non_negative(text, "um");
  if (std::isnan(v))
    bad_option(field, "expected a non-negative length in µm (e.g. 0.5µm), got '" + text + "'");
  return v;
}

// --conventions real: the campaign as laser software reports it
// (sim/real_conventions.hpp); the truth file keeps the true reflector points.
struct ConventionOptions {
  std::string conventions = "absolute";
  double reflector_error_mm = 0.0;
  std::uint64_t reflector_seed = 1;
};

void write_campaign(const sim::GeneratedMachine& g, const std::string& dir,
                    const ConventionOptions& conv = {}) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) bad_option("-o", "cannot create directory '" + dir + "': " + ec.message());
  sim::CampaignResult result = sim::run_campaign(g);
  const std::filesystem::path d(dir);
  sim::write_text_file_atomically((d / "truth.yaml").string(), sim::truth_to_yaml(g));
  sim::GeneratedMachine recorded = g;
  if (conv.conventions == "real") {
    sim::RealConventions rc;
    rc.reflector_sigma_mm = conv.reflector_error_mm;
    rc.seed = conv.reflector_seed;
    const sim::ConventionRecord r = sim::apply_real_conventions(recorded, result, rc);
    spdlog::info(
        "real conventions: zeroed, straightness slopes removed, relative angles; squareness "
        "changed by EC0Y {:+.3f}, EB0Z {:+.3f}, EA0Z {:+.3f} µrad; reflector error σ = {} mm",
        r.squareness_change.ec0y, r.squareness_change.eb0z, r.squareness_change.ea0z,
        conv.reflector_error_mm);
  }
  sim::write_text_file_atomically((d / "runs.csv").string(), sim::runs_to_csv(result));
  sim::write_text_file_atomically((d / "errors.csv").string(), sim::table_to_csv(result));
  sim::write_text_file_atomically((d / "machine.yaml").string(),
                                  sim::machine_to_yaml(recorded, result, "errors.csv"));
  spdlog::info("wrote {}/{{truth.yaml,machine.yaml,errors.csv,runs.csv}} ({} readings)", dir,
               result.runs.size());
}

struct MachineOptions {
  sim::GeneratorOptions gen;
  std::string squareness_sigma;
  bool squareness_sigma_given = false;  // false: the profile's default
  std::vector<std::string> inject;
  std::string output;
};

struct CampaignOptions {
  std::string truth;
  std::string output;
  double spacing = 0.0;  // 0: keep
  int runs = 0;          // 0: keep
  double noise_scale = 1.0;
  std::string seed;  // empty: keep
  ConventionOptions conventions;
};

struct MeasureOptions {
  std::string truth;
  std::string output = "-";
  double grid = 0.0;
  std::string program;
  std::vector<double> box;
  double tool_length = NAN;
  std::vector<std::string> inject;
  std::string noise = "0.5um";
  std::uint64_t seed = 1;
  double interval = 5.0;
  int repeat = 1;
  bool one_setup = false;
  std::string set;
  double step = 5.0;
  gcode::DialectOptions dialect;
};

int run_machine(const MachineOptions& o) {
  sim::GeneratorOptions gen = o.gen;
  if (o.squareness_sigma_given) {
    gen.squareness_sigma_urad = parse_non_negative(o.squareness_sigma, "urad");
    if (std::isnan(*gen.squareness_sigma_urad))
      bad_option("--squareness-sigma",
                 "expected a finite number ≥ 0 in µrad (e.g. 2 or 2urad), got '" +
                     o.squareness_sigma + "'");
  }
  sim::GeneratedMachine g;
  try {
    g = sim::generate_machine(gen);
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    bad_option(what.find("chain") == 0              ? "--chain"
               : what.find("squareness sigma") == 0 ? "--squareness-sigma"
                                                    : "--like",
               what);
  }
  g.truth.effects = parse_effects(o.inject);
  write_campaign(g, o.output);
  return kOk;
}

int run_campaign_cmd(const CampaignOptions& o) {
  sim::GeneratedMachine g = sim::load_truth_file(o.truth);
  if (o.spacing > 0.0) g.campaign.spacing_mm = o.spacing;
  if (o.runs > 0) g.campaign.runs = o.runs;
  for (auto& a : g.campaign.axes)
    for (double& s : a.sigma) s *= o.noise_scale;
  g.campaign.squareness_sigma_urad *= o.noise_scale;
  if (!o.seed.empty()) {
    char* end = nullptr;
    errno = 0;
    const unsigned long long v = std::strtoull(o.seed.c_str(), &end, 10);
    if (end != o.seed.c_str() + o.seed.size() || errno != 0)
      bad_option("--seed", "expected a non-negative integer, got '" + o.seed + "'");
    g.campaign.seed = v;
  }
  write_campaign(g, o.output, o.conventions);
  return kOk;
}

int run_measure(const MeasureOptions& o) {
  sim::GeneratedMachine g = sim::load_truth_file(o.truth);
  sim::TruthMachine& truth = g.truth;
  for (const sim::Effect& e : parse_effects(o.inject)) truth.effects.push_back(e);
  const double noise = parse_um("--noise", o.noise);
  const double tool_length = std::isnan(o.tool_length) ? truth.tool_length : o.tool_length;
  std::vector<sim::TipState> tips;
  std::vector<std::size_t> program_lines;  // per tip, with --program: its line in the program
  if (!o.program.empty()) {
    gcode::InterpreterConfig config;
    config.tool_lengths = truth.tool_table;
    config.default_tool_length = tool_length;
    config.initial_position = Eigen::Vector3d(0.0, 0.0, -tool_length);
    InputStream input(o.program, "the NC program");  // "-": stdin
    std::istream& in = input.stream();
    pipeline::PathOptions po;
    if (!(o.step > 0.0)) bad_option("--step", "must be > 0 mm");
    po.fragment.step = o.step;
    po.dialect = o.dialect;
    const std::string set = o.set.empty() ? "program" : o.set;
    pipeline::run_path(in, o.program, config, po, [&](const path::PathPoint& p) {
      sim::TipState tip;
      tip.p = p.p;
      tip.tool_length = p.tool_length;
      for (std::size_t i = 0; i < 3; ++i) tip.dir[i] = p.dir[i];
      tip.time = p.time;
      tip.set = set;
      tips.push_back(tip);
      program_lines.push_back(p.line);
    });
  } else {
    sim::GridOptions go;
    go.spacing_mm = o.grid;
    go.tool_length = tool_length;
    go.interval_s = o.interval;
    go.repeat = o.repeat;
    go.one_setup = o.one_setup;
    if (!o.set.empty()) go.set = o.set;
    if (o.repeat < 1) bad_option("--repeat", "must be ≥ 1");
    if (!(o.interval >= 0.0)) bad_option("--interval", "must be ≥ 0 s");
    sim::default_box(truth, tool_length, go.lo, go.hi);
    if (!o.box.empty()) parse_box_option(o.box, go.lo, go.hi);
    if (!(go.spacing_mm > 0.0)) bad_option("--grid", "grid spacing must be > 0 mm");
    tips = sim::grid_points(go);
    if (tips.size() > 5'000'000)
      bad_option("--grid", "more than 5 million points; use a coarser grid");
  }
  const auto points = sim::measure(truth, tips, noise, o.seed);
  sim::write_text_file_atomically(o.output, sim::measured_to_csv(points));
  spdlog::info("measured {} points", points.size());
  // A real machine cannot measure beyond its travel: say so (the lines are
  // the program's, or the output file's for a grid).
  std::array<machine::Travel, 3> travel;
  for (std::size_t a = 0; a < 3; ++a)
    travel[a] = {truth.axes[a].travel_min, truth.axes[a].travel_max};
  machine::TravelCheck check(travel);
  for (std::size_t i = 0; i < tips.size(); ++i)
    check.add(tips[i].p, tips[i].tool_length, program_lines.empty() ? i + 2 : program_lines[i]);
  if (check.outside())
    spdlog::warn("{}: {}: the machine cannot go there (the truth's errors there are extrapolated)",
                 !program_lines.empty()                ? o.program
                 : o.output.empty() || o.output == "-" ? "<stdout>"
                                                       : o.output,
                 check.text());
  return kOk;
}

const CommandRegistrar registrar(
    "simulate",
    "Virtual machine: generate a SYNTHETIC ground truth and its laser campaign, or measure it "
    "with injected effects",
    70, [](CLI::App& sub, const GlobalOptions&) -> CommandAction {
      sub.require_subcommand(1);
      auto mo = std::make_shared<MachineOptions>();
      CLI::App* machine = sub.add_subcommand(
          "machine",
          "Generate a truth machine and run its laser campaign: writes DIR/truth.yaml, "
          "machine.yaml, errors.csv, runs.csv");
      machine->footer("Example: abbe simulate machine --like mazak --seed 1 -o vm");
      machine->add_option("--seed", mo->gen.seed, "Random seed")->capture_default_str();
      machine->add_option("--like", mo->gen.profile, "Profile: mazak | generic")
          ->capture_default_str();
      machine->add_option("--chain", mo->gen.chain, "Kinematic chain (ISO 10791-1)")
          ->capture_default_str();
      machine->add_option("--spacing", mo->gen.spacing_mm, "Target interval, mm")
          ->capture_default_str();
      machine->add_option("--runs", mo->gen.runs, "Runs per direction")->capture_default_str();
      machine
          ->add_option("--noise-scale", mo->gen.noise_scale,
                       "Multiplies the reading noise (0: noise-free)")
          ->capture_default_str();
      machine
          ->add_option("--angular-scale", mo->gen.angular_scale,
                       "Multiplies the angular error motions (after calibration)")
          ->capture_default_str();
      auto* squareness_sigma =
          machine
              ->add_option(
                  "--squareness-sigma", mo->squareness_sigma,
                  "Noise of the squareness measurement, µrad, used as given (default: mazak "
                  "0 — the thesis' values as measured; generic 2 × --noise-scale)")
              ->option_text("URAD");
      machine->add_option("--inject", mo->inject,
                          "Effect stored in the truth, KIND:AXIS:MAG[:k=v,...] (repeatable)");
      machine->add_option("-o,--output", mo->output, "Output directory")->required();

      auto co = std::make_shared<CampaignOptions>();
      CLI::App* campaign = sub.add_subcommand(
          "campaign", "Re-run the laser campaign of a truth file (other spacing, runs, noise)");
      campaign->footer(
          "Example: abbe simulate campaign --truth machines/sample/truth.yaml -o campaign");
      campaign->add_option("--truth", co->truth, "Truth file (truth.yaml)")->required();
      campaign->add_option("--spacing", co->spacing, "Target interval, mm");
      campaign->add_option("--runs", co->runs, "Runs per direction");
      campaign->add_option("--noise-scale", co->noise_scale, "Multiplies the reading noise");
      campaign->add_option("--seed", co->seed, "Seed of the reading noise");
      campaign->add_option("-o,--output", co->output, "Output directory")->required();
      campaign
          ->add_option("--conventions", co->conventions.conventions,
                       "absolute (readings at exactly known reflectors) or real (zeroed, "
                       "straightness slopes removed, relative angles; docs/models.md)")
          ->check(CLI::IsMember({"absolute", "real"}))
          ->capture_default_str();
      campaign
          ->add_option("--reflector-error", co->conventions.reflector_error_mm,
                       "--conventions real: σ of the error of the recorded reflector points, mm")
          ->check(CLI::NonNegativeNumber);
      campaign->add_option("--reflector-seed", co->conventions.reflector_seed,
                           "Seed of the reflector errors");

      auto me = std::make_shared<MeasureOptions>();
      CLI::App* measure = sub.add_subcommand(
          "measure", "Measure the truth (with its effects and --inject ones): measured-data CSV");
      measure->footer(
          "Example: abbe simulate measure --truth machines/sample/truth.yaml --grid 100 -o "
          "measured.csv");
      measure->add_option("--truth", me->truth, "Truth file (truth.yaml)")->required();
      auto* grid = measure->add_option("--grid", me->grid,
                                       "Volumetric grid spacing, mm (default 50 with --box)");
      auto* program =
          measure->add_option("--program", me->program, "NC program: measure its fragmented path");
      grid->excludes(program);
      add_dialect_options(*measure, me->dialect);
      measure->add_option("--box", me->box, std::string("Grid only. ") + kBoxHelp)
          ->delimiter(',')
          ->expected(6);
      measure->add_option("--tool-length", me->tool_length,
                          "Tool length, mm (default: the machine's tool_length)");
      measure->add_option("--inject", me->inject, "Effect KIND:AXIS:MAG[:k=v,...] (repeatable)");
      measure->add_option("--noise", me->noise, "Gaussian noise per coordinate, e.g. 0.5µm")
          ->capture_default_str();
      measure->add_option("--seed", me->seed, "Noise seed")->capture_default_str();
      measure->add_option("--interval", me->interval, "Grid: seconds per measured point")
          ->capture_default_str();
      measure->add_option("--repeat", me->repeat, "Grid: measure it N times (sets <set>1..N)")
          ->capture_default_str();
      measure->add_flag("--one-setup", me->one_setup,
                        "Grid with --repeat: every pass in the one set (one setup, one datum)");
      measure->add_option("--set", me->set, "Set label (default grid | program)");
      measure->add_option("--step", me->step, "Program: fragmentation step, mm")
          ->capture_default_str();
      measure->add_option("-o,--output", me->output, "Output CSV (default stdout)");

      sub.footer(
          "Example: abbe simulate measure --truth machines/sample/truth.yaml --grid 100 "
          "-o measured.csv");
      return [machine, campaign, measure, mo, co, me, grid, program, squareness_sigma]() {
        if (machine->parsed()) {
          mo->squareness_sigma_given = squareness_sigma->count() > 0;
          return run_machine(*mo);
        }
        if (campaign->parsed()) return run_campaign_cmd(*co);
        if (measure->parsed()) {
          if (grid->count() == 0 && program->count() == 0) {
            if (me->box.empty())
              bad_option("--grid", "give --grid SPACING, --box … or --program FILE");
            me->grid = 50.0;  // --box alone: the default 50 mm grid
          }
          return run_measure(*me);
        }
        return static_cast<int>(kUsage);
      };
    });

}  // namespace
}  // namespace abbe::cli
