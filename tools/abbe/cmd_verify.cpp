// abbe verify: predicts a compensated program and measures its distance from
// the nominal path of the original (docs/compensation.md).
#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "abbe/compensate/path_verifier.hpp"
#include "abbe/compensate/provenance.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"
#include "command.hpp"
#include "dialect_option.hpp"
#include "model_option.hpp"
#include "progress.hpp"
#include "setup_options.hpp"

namespace abbe::cli {
namespace {

struct VerifyCliOptions {
  std::string input;
  std::string against;
  ModelOptions m;
  double tol_um = 1.0;
  bool check = false;
  compensate::VerifyOptions v;
  gcode::DialectOptions dialect;
  SetupOptions setup;
};

// verify reads each program twice (forward and backward pass): standard
// input ("-") and a file that cannot be re-read (a pipe, a terminal) are read
// into memory first.
std::unique_ptr<std::istream> open_input(const std::string& path) {
  std::ostringstream text;
  if (path == "-") {
    text << std::cin.rdbuf();
    return std::make_unique<std::istringstream>(text.str());
  }
  auto file = std::make_unique<std::ifstream>(path, std::ios::binary);
  if (!*file)
    throw InputError({path, 0, 0, "", ""},
                     std::string("cannot open the input: ") + std::strerror(errno));
  std::error_code ec;
  if (std::filesystem::is_regular_file(path, ec)) return file;
  text << file->rdbuf();
  if (file->bad()) throw InputError({path, 0, 0, "", ""}, "cannot read the input to the end");
  return std::make_unique<std::istringstream>(text.str());
}

int run_verify(const VerifyCliOptions& o, const GlobalOptions& g) {
  const machine::Machine machine = machine::Machine::load(o.m.machine);
  const model::ErrorModel model = make_model(o.m, machine);
  gcode::InterpreterConfig config = pipeline::interpreter_config(machine);
  config.dialect = o.dialect;
  apply_setup_options(o.setup, config);
  compensate::VerifyOptions vo = o.v;
  vo.tol_um = o.tol_um;
  if (o.input == "-" && o.against == "-")
    throw InputError({"<command line>", 0, 0, "--against", ""},
                     "only one of the two programs can be - (standard input)");
  const std::unique_ptr<std::istream> comp_file = open_input(o.input);
  const std::unique_ptr<std::istream> orig_file = open_input(o.against);
  // The provenance block: the machine files must be those it names.
  std::string origin;
  if (const auto p = compensate::read_provenance(*comp_file)) {
    auto current = compensate::machine_fingerprints(machine);
    if (!o.m.extend.empty())
      current.push_back(compensate::file_fingerprint("overlay-file", o.m.extend));
    compensate::check_machine_files(*p, o.input, current);
    compensate::check_setup(*p, o.input, compensate::setup_lines(config));
    origin =
        fmt::format("  compensated by abbe {} on {} (model {})\n", p->version, p->date, p->model);
  } else {
    origin = "  no provenance block: not written by abbe compensate, machine files not checked\n";
  }
  comp_file->clear();
  comp_file->seekg(0);
  // Progress on a terminal: bytes read of both programs, each read twice
  // (the forward and the backward pass).
  Progress progress("verify", 2 * (Progress::file_size(o.input) + Progress::file_size(o.against)),
                    !g.quiet);
  std::uint64_t bytes_read = 0;
  ProgressStreambuf comp_counted(comp_file->rdbuf(), progress, bytes_read);
  ProgressStreambuf orig_counted(orig_file->rdbuf(), progress, bytes_read);
  std::istream comp(&comp_counted), orig(&orig_counted);
  const compensate::VerifyStats s =
      compensate::verify_program(comp, o.input, orig, o.against, config, model, vo);
  progress.finish();
  warn_overlay_domain(model.extension());
  const double max = std::max(s.max_um, s.backward_max_um);
  const std::vector<std::string> failures = compensate::verify_failures(s, o.tol_um);
  std::string why;
  for (const auto& f : failures) why += "  FAIL: " + f + "\n";
  std::fputs(
      fmt::format(
          "{} against {} (model {}):\n{}"
          "  cutting moves, predicted compensated -> nominal: {} points, max {:.4f} µm (line {}), "
          "rms {:.4f} µm, {} beyond tol\n"
          "  cutting moves, nominal -> predicted compensated: {} points, max {:.4f} µm (line {}), "
          "rms {:.4f} µm, {} beyond tol\n"
          "{}  max {:.4f} µm, tol {} µm: {}\n",
          o.input, o.against,
          model::to_string(model.kind()) + (o.m.extend.empty() ? "" : " + " + o.m.extend), origin,
          s.points, s.max_um, s.max_line, s.rms_um, s.over_tol, s.backward_points,
          s.backward_max_um, s.backward_max_line, s.backward_rms_um, s.backward_over_tol, why, max,
          o.tol_um, failures.empty() ? "pass" : "FAIL")
          .c_str(),
      stdout);
  if (o.check && !failures.empty()) return kCheckFailed;
  return kOk;
}

const CommandRegistrar registrar(
    "verify", "Measure the predicted path of a compensated program against the nominal path", 41,
    [](CLI::App& sub, const GlobalOptions& g) -> CommandAction {
      auto o = std::make_shared<VerifyCliOptions>();
      sub.footer(
          "Example: abbe verify compensated.ngc --against nc-samples/thesis-toolpath-1.ngc "
          "--machine machines/sample/machine.yaml --tol 1 --check   (exit 4 if beyond --tol)");
      sub.add_option("input", o->input, "Compensated NC program (- for stdin)")->required();
      sub.add_option("--against", o->against, "The original NC program (- for stdin)")->required();
      add_dialect_options(sub, o->dialect);
      add_setup_options(sub, o->setup);
      add_model_options(sub, o->m,
                        "Predict with the extended model: add the effects of an overlay written by "
                        "`abbe diagnose --overlay`");
      sub.add_option("--tol", o->tol_um, "Tolerance, µm")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
      sub.add_option("--step", o->v.step, "Fragment step, mm")
          ->check(CLI::PositiveNumber)
          ->capture_default_str();
      sub.add_flag("--check", o->check, "Exit 4 if the max distance exceeds --tol");
      const GlobalOptions* gp = &g;
      return [o, gp] { return run_verify(*o, *gp); };
    });

}  // namespace
}  // namespace abbe::cli
