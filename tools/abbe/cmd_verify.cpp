// abbe verify: predicts a compensated program and measures its distance from
// the nominal path of the original (docs/compensation.md).
#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "abbe/compensate/path_verifier.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"
#include "command.hpp"
#include "dialect_option.hpp"
#include "model_option.hpp"
#include "progress.hpp"

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
};

// verify reads each program twice (it seeks back): standard input ("-") is
// read into memory first.
std::unique_ptr<std::istream> open_input(const std::string& path) {
  if (path == "-") {
    auto s = std::make_unique<std::stringstream>();
    *s << std::cin.rdbuf();
    return s;
  }
  auto f = std::make_unique<std::ifstream>(path, std::ios::binary);
  if (!*f)
    throw InputError({path, 0, 0, "", ""},
                     std::string("cannot open the input: ") + std::strerror(errno));
  return f;
}

int run_verify(const VerifyCliOptions& o, const GlobalOptions& g) {
  const machine::Machine machine = machine::Machine::load(o.m.machine);
  const model::ErrorModel model = make_model(o.m, machine);
  gcode::InterpreterConfig config = pipeline::interpreter_config(machine);
  config.dialect = o.dialect;
  compensate::VerifyOptions vo = o.v;
  vo.tol_um = o.tol_um;
  if (o.input == "-" && o.against == "-")
    throw InputError({"<command line>", 0, 0, "--against", ""},
                     "only one of the two programs can be - (standard input)");
  const auto comp_file = open_input(o.input);
  const auto orig_file = open_input(o.against);
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
  const double max = std::max(s.max_um, s.backward_max_um);
  std::fputs(
      fmt::format("{} against {} (model {}):\n"
                  "  predicted compensated -> nominal: {} points, max {:.4f} µm (line {}), "
                  "rms {:.4f} µm, {} beyond tol\n"
                  "  nominal -> predicted compensated: {} points, max {:.4f} µm (line {}), "
                  "rms {:.4f} µm, {} beyond tol\n"
                  "  max {:.4f} µm, tol {} µm: {}\n",
                  o.input, o.against,
                  model::to_string(model.kind()) + (o.m.extend.empty() ? "" : " + " + o.m.extend),
                  s.points, s.max_um, s.max_line, s.rms_um, s.over_tol, s.backward_points,
                  s.backward_max_um, s.backward_max_line, s.backward_rms_um, s.backward_over_tol,
                  max, o.tol_um, max <= o.tol_um ? "pass" : "FAIL")
          .c_str(),
      stdout);
  if (o.check && max > o.tol_um) return kCheckFailed;
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
