// abbe predict: the predicted deviation of the tool tip along an NC program
// (parse → interpret → fragment → error model, block by block) or at the
// points of a CSV file (a CMM or laser grid), for one error model or all
// three side by side. Output is streamed; a summary per model goes to stderr
// (stdout when -o names a file).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>
#include <string>

#include "abbe/diagnose/overlay_extension.hpp"
#include "abbe/io/atomic_file.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/model_kind.hpp"
#include "abbe/pipeline/aligned_prediction.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"
#include "abbe/pipeline/path_writer.hpp"
#include "abbe/pipeline/predict.hpp"
#include "abbe/pipeline/prediction_summary.hpp"
#include "abbe/pipeline/prediction_uncertainty.hpp"
#include "abbe/pipeline/prediction_writer.hpp"
#include "align_options.hpp"
#include "command.hpp"
#include "dialect_option.hpp"
#include "input_stream.hpp"
#include "model_option.hpp"
#include "output_options.hpp"
#include "progress.hpp"
#include "setup_options.hpp"

namespace abbe::cli {
namespace {

struct PredictOptions {
  std::string input;
  std::string machine;
  std::string model = "ae-arm";
  std::string output = "-";
  std::string format = "csv";
  std::string summary_json;
  std::string extend;  // overlay of effects found by `abbe diagnose` (docs/formats.md)
  double step = 5.0;
  double rapid_rate = 10000.0;
  bool points = false;  // input is a CSV of points even without the .csv extension
  bool summary_only = false;
  gcode::DialectOptions dialect;
  AlignCliOptions align;  // the part's set-up (docs/models.md, "The part")
  SetupOptions setup;
  std::size_t uncertainty = 0;  // Monte Carlo draws (0: no uncertainty)
  std::uint64_t seed = 1;       // of the draws
};

// predict --align: the points are written after the alignment is known.
// The points output (none with --summary-only): the file and its writer.
struct PointsOutput {
  std::unique_ptr<io::AtomicOutputFile> out;
  std::unique_ptr<pipeline::PredictionWriter> writer;
};

PointsOutput open_points(const PredictOptions& o, pipeline::PathFormat format,
                         const std::vector<model::ModelKind>& models, bool aligned,
                         bool uncertainty = false) {
  PointsOutput p;
  if (o.summary_only) return p;
  p.out = std::make_unique<io::AtomicOutputFile>(o.output);
  io::AtomicOutputFile* file = p.out.get();
  p.writer = std::make_unique<pipeline::PredictionWriter>(
      format, models, [file](const char* d, std::size_t n) { file->write(d, n); }, aligned,
      uncertainty);
  return p;
}

// Ends the points output with the summary, writes --summary-json and prints
// the table: to stdout unless the points go there.
void finish_outputs(const PredictOptions& o, pipeline::PredictionWriter* writer,
                    io::AtomicOutputFile* out, const std::string& json, const std::string& table) {
  if (writer) {
    writer->finish(json);
    out->commit();
  }
  if (!o.summary_json.empty()) io::write_file_atomically(o.summary_json, json + "\n");
  const bool points_on_stdout = writer && (o.output == "-" || o.output.empty());
  std::fputs(table.c_str(), points_on_stdout ? stderr : stdout);
}

int run_predict_aligned(const PredictOptions& o, const GlobalOptions& g,
                        const machine::Machine& machine, const pipeline::PredictOptions& po,
                        pipeline::PathFormat format, const pipeline::AlignOptions& ao) {
  InputStream input(o.input, "the input");
  PointsOutput points = open_points(o, format, po.models, true);
  auto& writer = points.writer;
  Progress progress("predict", 0, !g.quiet, "points");
  const pipeline::AlignedPrediction prediction = pipeline::predict_aligned(
      input.stream(), o.input, machine, po, ao,
      [&](const model::EvalPoint&, std::size_t, const pipeline::ModelSet& models) {
        if (progress.active() && (models.points() & 4095) == 0) progress.update(models.points());
      },
      [&](const model::EvalPoint& p, std::size_t line, const std::vector<model::Deviation>& devs,
          const std::vector<double>& norms, const std::vector<Eigen::Vector3d>& aligned) {
        if (writer) writer->write(p, line, devs, norms, aligned);
      });
  progress.finish();
  warn_overlay_domain(po.extension.get(), po.models.size());
  finish_outputs(o, writer.get(), points.out.get(), pipeline::summary_json(prediction),
                 pipeline::summary_table(prediction));
  return kOk;
}

// predict --uncertainty N [--align …]: the points are written after the draws.
int run_predict_uncertain(const PredictOptions& o, const GlobalOptions& g,
                          const machine::Machine& machine, const pipeline::PredictOptions& po,
                          pipeline::PathFormat format, const pipeline::AlignOptions& ao) {
  pipeline::UncertaintyOptions uo;
  uo.draws = o.uncertainty;
  uo.seed = o.seed;
  InputStream input(o.input, "the input");
  PointsOutput points =
      open_points(o, format, po.models, ao.method != pipeline::AlignMethod::none, true);
  auto& writer = points.writer;
  Progress progress("predict --uncertainty", o.uncertainty, !g.quiet, "draws");
  const pipeline::UncertainPrediction prediction = pipeline::predict_with_uncertainty(
      input.stream(), o.input, machine, po, uo, ao, {},
      [&](const model::EvalPoint& p, std::size_t line, const std::vector<model::Deviation>& devs,
          const std::vector<double>& norms, const std::vector<Eigen::Vector3d>& aligned,
          const std::vector<Eigen::Vector3d>& u, const std::vector<Eigen::Vector3d>& u_aligned) {
        if (!writer) return;
        if (ao.method == pipeline::AlignMethod::none)
          writer->write_uncertain(p, line, devs, norms, u);
        else
          writer->write_uncertain(p, line, devs, norms, aligned, u, u_aligned);
      },
      [&](std::size_t done) {
        if (progress.active()) progress.update(done);
      });
  progress.finish();
  finish_outputs(o, writer.get(), points.out.get(), pipeline::summary_json(prediction),
                 pipeline::summary_table(prediction));
  return kOk;
}

int run_predict(const PredictOptions& o, const GlobalOptions& g) {
  const machine::Machine machine = machine::Machine::load(o.machine);
  pipeline::PredictOptions po;
  po.models = model::parse_model_list(o.model);
  po.input = pipeline::predict_input_of(o.input, o.points);
  po.path.fragment.step = o.step;
  po.path.fragment.rapid_rate = o.rapid_rate;
  po.path.dialect = o.dialect;
  po.config = pipeline::interpreter_config(machine);
  apply_setup_options(o.setup, *po.config);
  const pipeline::PathFormat format = pipeline::parse_path_format(o.format);
  // --extend: every model carries the overlay's extra deviation.
  if (!o.extend.empty())
    po.extension = std::make_shared<const diagnose::OverlayExtension>(
        diagnose::Overlay::load(o.extend), machine);
  pipeline::AlignOptions ao;
  if (!align_options(o.align, "predict", ao)) return kUsage;
  if (o.uncertainty > 0) return run_predict_uncertain(o, g, machine, po, format, ao);
  if (ao.method != pipeline::AlignMethod::none)
    return run_predict_aligned(o, g, machine, po, format, ao);

  InputStream input(o.input, "the input");
  PointsOutput points = open_points(o, format, po.models, false);
  auto& writer = points.writer;

  // Progress on a terminal: bytes of the input file read, or points from stdin.
  const bool from_file = !input.from_stdin();
  Progress progress("predict", from_file ? Progress::file_size(o.input) : 0, !g.quiet,
                    from_file ? "bytes" : "points");
  const pipeline::PredictionSummary summary = pipeline::predict(
      input.stream(), o.input, machine, po,
      [&](const model::EvalPoint& p, std::size_t line, const pipeline::ModelSet& models) {
        if (writer) writer->write(p, line, models);
        if (!progress.active() || (models.points() & 4095) != 0) return;
        if (!from_file) return progress.update(models.points());
        const auto pos = input.position();
        if (pos >= 0) progress.update(static_cast<std::uint64_t>(pos));
      });
  progress.finish();
  warn_overlay_domain(po.extension.get(), po.models.size());
  finish_outputs(o, writer.get(), points.out.get(), pipeline::summary_json(summary),
                 pipeline::summary_table(summary));
  if (!summary.travel_text.empty())
    spdlog::warn(
        "{}: {}: the tables end at the travel (predicted there by the out-of-range "
        "policy) and the machine cannot go there",
        o.input, summary.travel_text);
  return kOk;
}

const CommandRegistrar registrar(
    "predict",
    "Predict the deviation of the tool tip along an NC program or at the points of a CSV file", 30,
    [](CLI::App& sub, const GlobalOptions& g) -> CommandAction {
      auto o = std::make_shared<PredictOptions>();
      const GlobalOptions* gp = &g;
      sub.footer(
          "Example: abbe predict nc-samples/thesis-toolpath-1.ngc "
          "--machine machines/sample/machine.yaml --model all -o predicted.csv");
      sub.add_option("input", o->input,
                     "NC program, or a CSV of points (x,y,z[,vx,vy,vz,tool_length]); - for stdin")
          ->required();
      sub.add_option("--machine", o->machine, "Machine file (YAML, docs/formats.md)")->required();
      sub.add_option("--model", o->model, "Error model: " + model::model_names_text(true))
          ->check(CLI::IsMember(model::model_names(true)))
          ->capture_default_str();
      add_output_option(sub, o->output, "Output file")->capture_default_str();
      add_format_option(sub, o->format, {"csv", "json"});
      sub.add_option("--step", o->step, "Largest distance between points along the path, mm")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
      sub.add_option("--rapid-rate", o->rapid_rate, "Rate of rapid motions for the time, mm/min")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
      add_dialect_options(sub, o->dialect);
      sub.add_flag("--points", o->points, "The input is a CSV of points (also for non-.csv names)");
      add_setup_options(sub, o->setup);
      sub.add_flag("--summary-only", o->summary_only, "Write no points, only the summary");
      sub.add_option("--summary-json", o->summary_json, "Also write the summary as JSON to FILE");
      sub.add_option("--extend", o->extend,
                     std::string("Add the effects of an overlay written by `abbe diagnose "
                                 "--overlay`") +
                         kOverlayDomainHelp);
      add_align_options(sub, o->align);
      sub.add_option(
             "--uncertainty", o->uncertainty,
             "Also propagate the campaign's uncertainty (machine file `uncertainty`, table "
             "column `uncertainty`) by Monte Carlo with N draws: u_dx,u_dy,u_dz per point, "
             "U (k = 2) of the summary; with --align, also of the deviation after the set-up "
             "(redone in every draw)")
          ->check(CLI::Range(std::size_t{2}, std::size_t{1000000}));
      sub.add_option("--seed", o->seed, "--uncertainty: seed of the draws (same seed, same output)")
          ->capture_default_str();
      return [o, gp] { return run_predict(*o, *gp); };
    });

}  // namespace
}  // namespace abbe::cli
