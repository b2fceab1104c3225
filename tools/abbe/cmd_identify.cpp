// abbe identify: the component errors of a machine identified from
// volumetric measured data (a LaserTRACER-type grid), either as the 12
// parameters of the dual-number paper's linear parametrisation (--param
// linear) or as piecewise-linear component tables (--param tables), with
// standard errors, condition number, rank and the combinations the data
// cannot separate (docs/identification.md).
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "abbe/identify/parameter_identification.hpp"
#include "abbe/identify/table_fit.hpp"
#include "abbe/io/atomic_file.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/io/measured_data.hpp"
#include "abbe/machine/machine.hpp"
#include "command.hpp"
#include "interpreter_options.hpp"
#include "output_options.hpp"

namespace abbe::cli {
namespace {

struct IdentifyCliOptions {
  std::string measured;
  std::string machine;
  std::string param = "linear";
  double knots = 50.0;
  std::string output;
  std::string table_out;
};

// JSON numbers: NaN/∞ become null.
nlohmann::json num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

std::vector<identify::Observation> observations(const io::MeasuredData& md,
                                                const machine::Machine& machine) {
  std::vector<identify::Observation> obs;
  for (const io::MeasuredRow& r : md.rows) {
    identify::Observation o;
    o.point.p = r.p;
    o.point.tool_length = std::isnan(r.tool_length) ? machine.tool_length() : r.tool_length;
    o.point.dir = r.v;
    bool any = false;
    for (int k = 0; k < 3; ++k) {
      o.has[static_cast<std::size_t>(k)] = r.has(k);
      o.d_um[k] = r.has(k) ? r.d[static_cast<std::size_t>(k)] : 0.0;
      any = any || r.has(k);
    }
    if (any) obs.push_back(o);
  }
  if (obs.empty())
    throw InputError({md.file, 0, 0, "dx", ""},
                     "no row has a deviation dx, dy or dz: nothing to identify from");
  return obs;
}

std::string fmt_cond(double c) { return std::isfinite(c) ? fmt::format("{:.3g}", c) : "inf"; }

int run_linear(const IdentifyCliOptions& o, const machine::Machine& machine,
               const std::vector<identify::Observation>& obs) {
  const identify::ChainExpansion chain(machine);
  const identify::ParamIdentification r = identify::identify_linear(chain, obs);
  const auto& f = r.final_fit;
  std::string text = fmt::format(
      "identify (linear parametrisation of the dual-number paper) on {}: {} points, {} values\n",
      machine.name(), r.n_points, r.n_values);
  nlohmann::json js = {{"param", "linear"},
                       {"machine", machine.name()},
                       {"measured", o.measured},
                       {"n_points", r.n_points},
                       {"n_values", r.n_values}};
  js["parameters"] = nlohmann::json::array();
  for (int i = 0; i < identify::kParamCount; ++i) {
    const bool ok = r.identifiable[static_cast<std::size_t>(i)];
    text += fmt::format("  {:<3} {:>12.5f} ± {:<10} {}{}\n", identify::param_name(i), r.p[i],
                        ok ? fmt::format("{:.5f}", r.stderr_p[i]) : "-", identify::param_unit(i),
                        ok ? "" : "   NOT IDENTIFIABLE");
    js["parameters"].push_back({{"name", identify::param_name(i)},
                                {"value", r.p[i]},
                                {"stderr", num(r.stderr_p[i])},
                                {"unit", identify::param_unit(i)},
                                {"identifiable", ok}});
  }
  text += fmt::format(
      "  rank {}/{}, condition number {} (within the rank {}), residual RMS {:.4f} µm, max {:.4f} "
      "µm, {} Gauss–Newton iterations\n",
      f.rank, identify::kParamCount, fmt_cond(f.condition), fmt_cond(f.condition_in_rank),
      r.residual_rms_um, r.residual_max_um, r.iterations);
  js["rank"] = f.rank;
  js["condition"] = num(f.condition);
  js["condition_in_rank"] = num(f.condition_in_rank);
  js["residual_rms_um"] = r.residual_rms_um;
  js["residual_max_um"] = r.residual_max_um;
  js["sigma_um"] = f.sigma;
  js["iterations"] = r.iterations;
  js["unidentifiable"] = nlohmann::json::array();
  const auto names = identify::param_names();
  for (const auto& nd : f.null_space) {
    const std::string d = identify::describe_combination(nd.direction_scaled, names);
    text += fmt::format("  unidentifiable combination (unit-sensitivity scale): {}\n", d);
    js["unidentifiable"].push_back(d);
  }
  // The paper's monomial systems.
  js["monomial_systems"] = nlohmann::json::array();
  const char* comp[] = {"dx", "dy", "dz"};
  for (int k = 0; k <= 3; ++k) {
    const identify::MonomialFit& mf =
        k < 3 ? r.per_component[static_cast<std::size_t>(k)] : r.joint;
    const char* label = k < 3 ? comp[k] : "joint";
    text += fmt::format("  monomial system {:<5}: {} × {}, rank {}, condition {}\n", label,
                        mf.fit.rows, mf.monomials.size(), mf.fit.rank, fmt_cond(mf.fit.condition));
    js["monomial_systems"].push_back({{"system", label},
                                      {"rows", mf.fit.rows},
                                      {"columns", identify::monomial_names(mf.monomials)},
                                      {"rank", mf.fit.rank},
                                      {"condition", num(mf.fit.condition)}});
  }
  js["product_consistency"] = r.product_consistency;
  if (!o.output.empty()) io::write_file_atomically(o.output, js.dump(2) + "\n");
  std::fputs(text.c_str(), summary_stream(o.output));
  return kOk;
}

int run_tables(const IdentifyCliOptions& o, const machine::Machine& machine,
               const std::vector<identify::Observation>& obs) {
  const identify::ChainExpansion chain(machine);
  identify::TableFitOptions to;
  to.knot_spacing_mm = o.knots;
  const identify::TableFit t = identify::fit_component_tables(chain, obs, to);
  std::string text = fmt::format(
      "identify (piecewise-linear component tables, knots every {:g} mm) on {}: {} values, {} "
      "unknowns\n",
      o.knots, machine.name(), t.n_values, t.unknowns);
  text += fmt::format(
      "  rank {}/{}, condition number {} (within the rank {}), residual RMS {:.4f} µm, max {:.4f} "
      "µm\n",
      t.fit.rank, t.unknowns, fmt_cond(t.fit.condition), fmt_cond(t.fit.condition_in_rank),
      t.residual_rms_um, t.residual_max_um);
  nlohmann::json js = {{"param", "tables"},
                       {"machine", machine.name()},
                       {"measured", o.measured},
                       {"knot_spacing_mm", o.knots},
                       {"n_values", t.n_values},
                       {"unknowns", t.unknowns},
                       {"rank", t.fit.rank},
                       {"condition", num(t.fit.condition)},
                       {"residual_rms_um", t.residual_rms_um},
                       {"residual_max_um", t.residual_max_um}};
  js["components"] = nlohmann::json::array();
  text += "  component  separable      max |value|  confounded with\n";
  for (std::size_t c = 0; c < t.series.size(); ++c) {
    const auto& s = t.series[c];
    const auto& sep = t.separability[c];
    double vmax = 0.0;
    for (double v : s.value) vmax = std::max(vmax, std::abs(v));
    std::string with;
    for (const auto& w : sep.confounded_with) with += (with.empty() ? "" : " ") + w;
    // yes: no shape of it is lost; no: (nearly) every shape is; partly: a few
    // (typically its constant part or slope, traded with other components).
    const std::string verdict = sep.null_share < 0.05 ? "yes"
                                : sep.null_dims >= sep.knots - 1
                                    ? "no"
                                    : fmt::format("partly ({}/{})", sep.null_dims, sep.knots);
    text += fmt::format("  {:<9}  {:<13}  {:>11.4f}  {}\n", machine::component_name(s.id), verdict,
                        vmax, with);
    js["components"].push_back({{"component", machine::component_name(s.id)},
                                {"separable", verdict},
                                {"null_share", sep.null_share},
                                {"null_dims", sep.null_dims},
                                {"confounded_with", sep.confounded_with},
                                {"knots_mm", s.knots_mm},
                                {"value", s.value}});
  }
  text += fmt::format("  {} unidentifiable directions (the fit keeps angular errors smallest)\n",
                      t.fit.null_space.size());
  js["unidentifiable"] = t.unidentifiable;
  if (!o.table_out.empty()) io::write_file_atomically(o.table_out, identify::table_fit_to_csv(t));
  if (!o.output.empty()) io::write_file_atomically(o.output, js.dump(2) + "\n");
  std::fputs(text.c_str(), summary_stream(o.output));
  return kOk;
}

int run_identify(const IdentifyCliOptions& o) {
  const machine::Machine machine = machine::Machine::load(o.machine);
  if (!(o.knots > 0.0)) bad_option("--knots", "knot spacing must be > 0 mm");
  if (o.param == "linear" && !o.table_out.empty())
    bad_option("--table-out", "--table-out needs --param tables");
  const io::MeasuredData md = io::load_measured_data(o.measured);
  const auto obs = observations(md, machine);
  return o.param == "linear" ? run_linear(o, machine, obs) : run_tables(o, machine, obs);
}

const CommandRegistrar registrar(
    "identify",
    "Identify the error parameters (linear parametrisation or tables) from volumetric data", 55,
    [](CLI::App& sub, const GlobalOptions&) -> CommandAction {
      auto o = std::make_shared<IdentifyCliOptions>();
      sub.footer(
          "Example: abbe identify --measured machines/sample/measured-grid.csv "
          "--machine machines/sample/machine.yaml -o identified.json");
      sub.add_option("--measured", o->measured, "Measured-data CSV (docs/formats.md; - for stdin)")
          ->required();
      sub.add_option("--machine", o->machine, "Machine file (YAML): chain, arms, squareness, L")
          ->required();
      sub.add_option("--param", o->param, "linear (12 parameters) or tables (component tables)")
          ->check(CLI::IsMember({"linear", "tables"}))
          ->capture_default_str();
      sub.add_option("--knots", o->knots, "Knot spacing of the fitted tables, mm")
          ->capture_default_str();
      add_output_option(sub, o->output, "Result as JSON");
      sub.add_option("--table-out", o->table_out,
                     "Fitted component table CSV (--param tables), readable by predict");
      return [o] { return run_identify(*o); };
    });

}  // namespace
}  // namespace abbe::cli
