// abbe iso230: ISO 230-2 evaluation of bidirectional laser runs.
#include <fstream>
#include <iostream>
#include <string>

#include "abbe/diagnose/iso230.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/sim/text_file.hpp"
#include "command.hpp"
#include "output_options.hpp"

namespace abbe::cli {
namespace {

struct Iso230Options {
  std::string runs;
  std::string output = "-";
  bool json = false;  // --json, the old spelling of --format json
  std::string format;
  bool per_target = false;
};

int run_iso230(const Iso230Options& o) {
  std::vector<diagnose::Iso230Reading> readings;
  if (o.runs == "-") {
    readings = diagnose::read_iso230_runs(std::cin, "-");
  } else {
    std::ifstream in(o.runs);
    if (!in) {
      SourceLocation where;
      where.file = o.runs;
      throw InputError(where, "cannot open the runs file");
    }
    readings = diagnose::read_iso230_runs(in, o.runs);
  }
  const auto results = diagnose::evaluate_iso230(readings, o.runs);
  const bool json = o.json || o.format == "json" || o.per_target;
  const std::string text =
      json ? diagnose::iso230_to_json(results, o.per_target) : diagnose::iso230_to_text(results);
  sim::write_text_file_atomically(o.output, text);
  return kOk;
}

const CommandRegistrar registrar(
    "iso230",
    "ISO 230-2 evaluation of laser runs (accuracy A, repeatability R, reversal B, "
    "systematic error E, mean deviation M)",
    60, [](CLI::App& sub, const GlobalOptions&) -> CommandAction {
      auto o = std::make_shared<Iso230Options>();
      sub.footer("Example: abbe iso230 machines/sample/runs.csv --format json -o iso230.json");
      sub.add_option("runs", o->runs,
                     "Runs CSV: axis,component,target_mm,run,direction,deviation ('-' = stdin)")
          ->required();
      add_format_option(sub, o->format, {"text", "json"});
      sub.add_flag("--json", o->json, "")->group("");  // old spelling of --format json
      sub.add_flag("--per-target", o->per_target, "JSON with the per-target values too");
      add_output_option(sub, o->output, "The table or JSON (default stdout)");
      return [o] { return run_iso230(*o); };
    });

}  // namespace
}  // namespace abbe::cli
