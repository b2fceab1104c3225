// abbe report: a self-contained HTML page of plots and tables (inline SVG,
// no network needed) — `report predict` for an NC program (toolpath with the
// deviation exaggerated, deviation along the path, summary per model) and
// `report map` for the workspace (colour maps of |d| on slices, htm and
// ae-arm side by side). See docs/report.md.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "abbe/diagnose/iso230.hpp"
#include "abbe/identify/workspace_map.hpp"
#include "abbe/io/atomic_file.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/io/measured_data.hpp"
#include "abbe/io/sha256.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/report/compensate_section.hpp"
#include "abbe/report/diagnose_section.hpp"
#include "abbe/report/html_page.hpp"
#include "abbe/report/iso230_section.hpp"
#include "abbe/report/map_section.hpp"
#include "abbe/report/predict_section.hpp"
#include "abbe/report/predicted_path.hpp"
#include "align_options.hpp"
#include "command.hpp"
#include "dialect_option.hpp"
#include "input_stream.hpp"
#include "progress.hpp"
#include "table_uncertainty_option.hpp"

namespace abbe::cli {
namespace {

struct ReportOptions {
  std::string input;
  std::string machine;
  std::string model = "all";
  std::string output;
  std::string compensated;
  double exaggerate = 0.0;  // ≤ 0: automatic
  double tolerance = 0.0;   // µm, ≤ 0: automatic
  double step = 5.0;
  double grid = 50.0;
  double tool_length = -1.0;
  std::size_t max_points = 5000;
  gcode::DialectOptions dialect;
  std::size_t uncertainty = 0;  // report predict: Monte Carlo draws (0: none)
  long table_draws = -1;        // report diagnose --table-uncertainty; -1: not given
  std::uint64_t seed = 1;
  AlignCliOptions align;  // report predict: the part's set-up
};

std::vector<model::ModelKind> parse_models(const std::string& m) {
  return model::parse_model_list(m);
}

// The command line as typed (Linux: /proc/self/cmdline), arguments with
// spaces or quotes in single quotes.
std::string command_line() {
  std::ifstream f("/proc/self/cmdline", std::ios::binary);
  std::string all{std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
  std::string out;
  std::size_t start = 0;
  while (start < all.size()) {
    std::size_t end = all.find('\0', start);
    if (end == std::string::npos) end = all.size();
    std::string arg = all.substr(start, end - start);
    if (start == 0) {  // the program: its file name
      const std::size_t slash = arg.rfind('/');
      if (slash != std::string::npos) arg = arg.substr(slash + 1);
    }
    if (!out.empty()) out += ' ';
    if (arg.empty() || arg.find_first_of(" \t'\"$\\;&|<>*?") != std::string::npos) {
      std::string q = "'";
      for (char c : arg) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
      out += q + "'";
    } else {
      out += arg;
    }
    start = end + 1;
  }
  return out.empty() ? "abbe report" : out;
}

// The footer: command line and SHA-256 of each input file ("-": the hash of
// the bytes read, when known).
void set_provenance(report::HtmlPage& page,
                    const std::vector<std::pair<std::string, std::string>>& hashed) {
  report::Provenance p;
  p.command_line = command_line();
  p.inputs = hashed;
  page.set_provenance(std::move(p));
}

std::pair<std::string, std::string> hashed_file(const std::string& path) {
  return {path, io::sha256_file(path)};
}

void write_page(const std::string& path, const report::HtmlPage& page) {
  const std::string html = page.render();
  io::write_file_atomically(path, html);
  if (path != "-") spdlog::info("wrote {} ({} kB)", path, (html.size() + 512) / 1024);
}

int run_report_predict(const ReportOptions& o, const GlobalOptions& g) {
  const machine::Machine machine = machine::Machine::load(o.machine);
  report::PredictPathOptions po;
  po.models = parse_models(o.model);
  po.step = o.step;
  po.max_points = o.max_points;
  po.dialect = o.dialect;
  po.uncertainty_draws = o.uncertainty;
  po.seed = o.seed;
  if (!align_options(o.align, "report predict", po.align)) return kUsage;
  InputStream input(o.input, "the NC program");
  std::istream* in = &input.stream();
  Progress progress("report: predict", Progress::file_size(o.input), !g.quiet);
  po.progress = [&](std::uint64_t bytes) { progress.update(bytes); };
  const report::PredictedPath path = report::predict_program(machine, *in, o.input, po);
  progress.finish();
  report::HtmlPage page(fmt::format("abbe: predicted toolpath of {}", o.input));
  report::render_predict_report(page, path, o.exaggerate, o.tolerance);
  set_provenance(
      page, {{o.input == "-" ? "standard input" : o.input, path.sha256}, hashed_file(o.machine)});
  write_page(o.output, page);
  return kOk;
}

int run_report_map(const ReportOptions& o) {
  const machine::Machine machine = machine::Machine::load(o.machine);
  identify::MapOptions mo;
  mo.models = parse_models(o.model);
  if (!(o.grid > 0.0))
    throw InputError({"<command line>", 0, 0, "--grid", ""}, "grid spacing must be > 0 mm");
  mo.spacing_mm = o.grid;
  mo.tool_length = o.tool_length >= 0.0 ? o.tool_length : machine.tool_length();
  identify::travel_box(machine, mo.tool_length, mo.lo, mo.hi);
  double n = 1.0;
  for (int i = 0; i < 3; ++i) n *= std::floor((mo.hi[i] - mo.lo[i]) / mo.spacing_mm) + 2.0;
  if (n > 2e6)
    throw InputError({"<command line>", 0, 0, "--grid", ""},
                     "more than 2 million grid points; use a coarser grid");
  const identify::WorkspaceMap map = identify::compute_map(machine, mo);
  report::HtmlPage page(fmt::format("abbe: workspace error map of {}", machine.name()));
  page.add_fact("tool length", fmt::format("{:g} mm", mo.tool_length));
  report::render_map_report(page, map, machine.name());
  set_provenance(page, {hashed_file(o.machine)});
  write_page(o.output, page);
  return kOk;
}

std::string read_text(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f)
    throw InputError({path, 0, 0, "", ""},
                     std::string("cannot open the NC program: ") + std::strerror(errno));
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

int run_report_compensate(const ReportOptions& o) {
  const machine::Machine machine = machine::Machine::load(o.machine);
  report::PredictPathOptions po;
  po.models = parse_models(o.model);
  if (po.models.size() != 1)
    throw InputError({"<command line>", 0, 0, "--model", ""},
                     "report compensate takes one model (" + model::model_names_text(false) + ")");
  po.step = o.step;
  po.max_points = 20000;  // the distance statistics are over the kept points
  const report::CompensationComparison c = report::compare_compensation(
      machine, read_text(o.input), o.input, read_text(o.compensated), o.compensated, po);
  report::HtmlPage page(fmt::format("abbe: compensation of {}", o.input));
  report::render_compensate_report(page, c, o.exaggerate);
  set_provenance(page, {hashed_file(o.input), hashed_file(o.compensated), hashed_file(o.machine)});
  write_page(o.output, page);
  return kOk;
}

int run_report_diagnose(const ReportOptions& o) {
  const machine::Machine machine = machine::Machine::load(o.machine);
  const io::MeasuredData data = io::load_measured_data(o.input);
  diagnose::DiagnoseOptions dopt;
  const auto kinds = parse_models(o.model);
  if (kinds.size() != 1)
    throw InputError({"<command line>", 0, 0, "--model", ""},
                     "report diagnose takes one model (" + model::model_names_text(false) + ")");
  dopt.model = kinds.front();
  dopt.tables = table_uncertainty_options(o.table_draws, o.seed);
  const report::DiagnosisForReport d = report::diagnose_for_report(machine, data, dopt);
  report::HtmlPage page(fmt::format("abbe: diagnosis of {}", o.input));
  report::render_diagnose_report(page, d);
  set_provenance(page, {hashed_file(o.input), hashed_file(o.machine)});
  write_page(o.output, page);
  return kOk;
}

int run_report_iso230(const ReportOptions& o) {
  std::string text;
  if (o.input == "-") {
    text.assign(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
  } else {
    std::ifstream f(o.input, std::ios::binary);
    if (!f)
      throw InputError({o.input, 0, 0, "", ""},
                       std::string("cannot open the runs file: ") + std::strerror(errno));
    text.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  }
  std::istringstream in(text);
  const auto readings = diagnose::read_iso230_runs(in, o.input);
  const auto results = diagnose::evaluate_iso230(readings, o.input);
  report::HtmlPage page(fmt::format("abbe: ISO 230-2 evaluation of {}", o.input));
  report::render_iso230_report(page, results);
  set_provenance(page, {{o.input == "-" ? "standard input" : o.input, io::sha256_hex(text)}});
  write_page(o.output, page);
  return kOk;
}

const CommandRegistrar registrar(
    "report",
    "Write an HTML report: a program's predicted toolpath (3-D), a workspace map, a "
    "compensation, a diagnosis or an ISO 230-2 evaluation",
    80, [](CLI::App& sub, const GlobalOptions& g) -> CommandAction {
      auto o = std::make_shared<ReportOptions>();
      const GlobalOptions* gp = &g;
      sub.require_subcommand(1);
      sub.footer(
          "Example: abbe report predict nc-samples/thesis-toolpath-1.ngc "
          "--machine machines/sample/machine.yaml -o report.html");
      CLI::App* predict = sub.add_subcommand(
          "predict", "Toolpath (3-D and planes, deviation exaggerated), deviation along the path");
      predict->add_option("program", o->input, "NC program, - for stdin")->required();
      predict->add_option("--machine", o->machine, "Machine file (YAML)")->required();
      add_dialect_options(*predict, o->dialect);
      predict->add_option("--model", o->model, model::model_names_text(true))
          ->check(CLI::IsMember(model::model_names(true)))
          ->capture_default_str();
      predict->add_option("--exaggerate", o->exaggerate,
                          "Draw nominal + K·deviation (default: automatic)");
      predict
          ->add_option("--tolerance", o->tolerance,
                       "Colour the 3-D toolpath by |d| against this tolerance, µm (default: "
                       "the largest max |d| rounded up to 2 digits; changeable in the page)")
          ->check(CLI::PositiveNumber);
      predict->add_option("--step", o->step, "Largest distance between points, mm")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
      predict->add_option("--max-points", o->max_points, "Most points drawn (thinned beyond)")
          ->check(CLI::Range(16, 1000000))
          ->capture_default_str();
      predict
          ->add_option("--uncertainty", o->uncertainty,
                       "Also propagate the campaign's uncertainty by Monte Carlo with N draws "
                       "(as `abbe predict --uncertainty`): the band ± U (k = 2) in the deviation "
                       "plots, the summary figures ± U; with --align also of the deviation after "
                       "the set-up")
          ->check(CLI::Range(std::size_t{2}, std::size_t{1000000}));
      predict->add_option("--seed", o->seed, "--uncertainty: seed of the draws")
          ->capture_default_str();
      add_align_options(*predict, o->align);
      predict->add_option("-o,--output", o->output, "HTML file (written atomically), - for stdout")
          ->required();
      predict->footer(
          "Example: abbe report predict nc-samples/thesis-toolpath-1.ngc "
          "--machine machines/sample/machine.yaml --model all --exaggerate 2000 --tolerance 20 "
          "-o report.html");
      CLI::App* map = sub.add_subcommand(
          "map", "Colour maps of |d| on slices of the workspace, htm and ae-arm side by side");
      map->add_option("--machine", o->machine, "Machine file (YAML)")->required();
      map->add_option("--grid", o->grid, "Grid spacing, mm")->capture_default_str();
      map->add_option("--tool-length", o->tool_length, "Tool length, mm (default: the machine's)");
      map->add_option("--model", o->model, model::model_names_text(true))
          ->check(CLI::IsMember(model::model_names(true)))
          ->capture_default_str();
      map->add_option("-o,--output", o->output, "HTML file (written atomically), - for stdout")
          ->required();
      map->footer(
          "Example: abbe report map --machine machines/sample/machine.yaml --grid 50 -o map.html");
      CLI::App* comp = sub.add_subcommand(
          "compensate", "Nominal, predicted original and predicted compensated toolpath");
      comp->add_option("program", o->input, "The original NC program")->required();
      comp->add_option("--compensated", o->compensated,
                       "The compensated program (output of abbe compensate)")
          ->required();
      comp->add_option("--machine", o->machine, "Machine file (YAML)")->required();
      comp->add_option("--model", o->model,
                       model::model_names_text(false) + " (as given to abbe compensate)")
          ->check(CLI::IsMember(model::model_names(false)))
          ->default_str("ae-arm");
      comp->add_option("--exaggerate", o->exaggerate, "Draw deviations × K (default: automatic)");
      comp->add_option("--step", o->step, "Largest distance between points, mm")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
      comp->add_option("-o,--output", o->output, "HTML file (written atomically), - for stdout")
          ->required();
      comp->footer(
          "Example: abbe compensate nc-samples/thesis-toolpath-1.ngc --machine "
          "machines/sample/machine.yaml -o comp.ngc && abbe report compensate "
          "nc-samples/thesis-toolpath-1.ngc --compensated comp.ngc --machine "
          "machines/sample/machine.yaml -o compensation.html");
      CLI::App* diag = sub.add_subcommand(
          "diagnose", "Residual against each variable before/after the extension, effect table");
      diag->add_option("--measured", o->input, "Measured data (CSV, docs/formats.md)")->required();
      diag->add_option("--machine", o->machine, "Machine file (YAML)")->required();
      diag->add_option("--model", o->model, model::model_names_text(false))
          ->check(CLI::IsMember(model::model_names(false)))
          ->default_str("ae-arm");
      add_table_uncertainty_option(*diag, o->table_draws);
      diag->add_option("--seed", o->seed, "--table-uncertainty: seed of the draws")
          ->capture_default_str();
      diag->add_option("-o,--output", o->output, "HTML file (written atomically), - for stdout")
          ->required();
      diag->footer(
          "Example: abbe report diagnose --measured machines/sample/measured-grid.csv "
          "--machine machines/sample/machine.yaml -o diagnosis.html");
      CLI::App* iso = sub.add_subcommand(
          "iso230", "ISO 230-2 chart (mean ± 2s per direction per target) and A/B/R/E/M table");
      iso->add_option("runs", o->input,
                      "Runs CSV: axis,component,target_mm,run,direction,deviation ('-' = stdin)")
          ->required();
      iso->add_option("-o,--output", o->output, "HTML file (written atomically), - for stdout")
          ->required();
      iso->footer("Example: abbe report iso230 machines/sample/runs.csv -o iso230.html");
      return [o, gp, predict, map, comp, diag, iso]() -> int {
        if (iso->parsed()) return run_report_iso230(*o);
        if (diag->parsed()) {
          if (o->model == "all") o->model = "ae-arm";
          return run_report_diagnose(*o);
        }
        if (predict->parsed()) return run_report_predict(*o, *gp);
        if (map->parsed()) return run_report_map(*o);
        if (comp->parsed()) {
          if (o->model == "all") o->model = "ae-arm";
          return run_report_compensate(*o);
        }
        return kUsage;
      };
    });

}  // namespace
}  // namespace abbe::cli
