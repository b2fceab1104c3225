// The diagnosis report: JSON with the DESIGN.md §4 keys and the human summary.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "abbe/diagnose/diagnosis.hpp"

namespace abbe::diagnose {

namespace {
std::string direction_of(const Term& t) {
  if (t.direction >= 0) return std::string(1, axis_name(t.direction));
  return "";
}
std::string axis_of(const Term& t) {
  if (t.kind == TermKind::model_choice) return "";
  return t.axis >= 0 ? std::string(1, axis_name(t.axis)) : "";
}
const char* unit_of(const std::string& param) {
  if (param == "ppm") return " ppm";
  if (param == "urad") return " µrad";
  if (param == "um" || param == "amplitude_um") return " µm";
  if (param == "um_per_h") return " µm/h";
  if (param == "mm") return " mm";
  return "";
}

// The data's and the tables' parts of a term's parameter uncertainties
// (param_stderr of the term with each part alone); empty when the tables'
// uncertainty was not propagated.
using ParamValues = std::vector<std::pair<std::string, double>>;
std::pair<ParamValues, ParamValues> stderr_parts(const SelectedTerm& st) {
  if (st.stderr_tables.empty()) return {};
  Term data = st.term, tables = st.term;
  data.stderr_ = st.stderr_data;
  tables.stderr_ = st.stderr_tables;
  data.searched_stderr =
      st.searched_stderr_data >= 0.0 ? st.searched_stderr_data : st.term.searched_stderr;
  tables.searched_stderr = std::max(st.searched_stderr_tables, 0.0);
  return {data.param_stderr(), tables.param_stderr()};
}

std::string status_of(const SelectedTerm& st) {
  if (!st.ambiguous_with.empty()) return "ambiguous";
  return st.significant ? "named" : "not_significant";
}

}  // namespace

std::string effect_value_text(const Term& t) {
  const auto p = t.params();
  const auto e = t.param_stderr();
  if (p.empty() || e.empty() || e[0].first != p[0].first) return "-";
  return fmt::format("{:+.3g} ± {:.2g}{}", p[0].second, e[0].second, unit_of(p[0].first));
}

bool value_significant(const Term& t) {
  const auto p = t.params();
  const auto e = t.param_stderr();
  if (p.empty() || e.empty() || e[0].first != p[0].first) return true;
  return std::abs(p[0].second) > e[0].second;
}

std::string uncertainty_parts_text(const SelectedTerm& st) {
  const auto [data, tables] = stderr_parts(st);
  if (data.empty() || data.size() != tables.size()) return "";
  std::string parts;
  for (std::size_t i = 0; i < data.size(); ++i) {
    const std::string& name = data[i].first;
    // The value (first parameter) and a searched period or time constant.
    if (i > 0 && name != "period_mm" && name != "tau_s") continue;
    const char* unit = name == "tau_s" ? " s" : name == "period_mm" ? " mm" : unit_of(name);
    parts += fmt::format("{}{} {:.2g} and {:.2g}{}", parts.empty() ? "" : "; ",
                         i == 0            ? std::string("value")
                         : name == "tau_s" ? "τ"
                                           : "period",
                         data[i].second, tables[i].second, unit);
  }
  return "u from the data and from the tables: " + parts;
}

std::string period_unresolved_text(const SelectedTerm& st) {
  if (st.other_periods_mm.empty() || !st.ambiguous_with.empty()) return "";
  std::string periods;
  for (double p : st.other_periods_mm)
    periods += fmt::format("{}{:.4g} mm", periods.empty() ? "" : ", ", p);
  return fmt::format("period not resolved: {} {} as well", periods,
                     st.other_periods_mm.size() == 1 ? "fits" : "fit");
}

// The parts of a smooth function's linear part whose value exceeds its
// uncertainty (all of them are in the JSON report); empty when none does or
// when they hold less than kLinearPartMinShare of the function.
std::string linear_part_text(const SelectedTerm& st) {
  if (st.linear_share < kLinearPartMinShare) return "";
  std::string parts;
  for (const Term& t : st.linear_parts)
    if (value_significant(t))
      parts += fmt::format("{}{} {}", parts.empty() ? "" : ", ", t.label(), effect_value_text(t));
  if (parts.empty()) return "";
  return fmt::format("its linear part ({:.0f} % of it; parts of a structure, not names): {}",
                     100.0 * st.linear_share, parts);
}

std::string isotropic_text(const Diagnosis& d) {
  const IsotropicScale& iso = d.isotropic;
  if (!iso.found) return "";
  std::string axes;
  for (std::size_t k = 0; k < iso.axes.size(); ++k)
    axes += fmt::format("{}scale {}{}", axes.empty() ? "" : ", ", axis_name(iso.axes[k]),
                        k < iso.from_linear_part.size() && iso.from_linear_part[k]
                            ? " (a smooth function's linear part)"
                            : "");
  return fmt::format(
      "isotropic scale: {} agree (χ² {:.2f} for {} degree{} of freedom): {:+.3g} ± {:.2g} ppm, "
      "consistent with one temperature difference ({:+.1f} K on steel at {:g} ppm/K, {:+.1f} K "
      "on aluminium at {:g} ppm/K) rather than a laser compensation error, which differs per "
      "axis\n",
      axes, iso.chi2, iso.axes.size() - 1, iso.axes.size() == 2 ? "" : "s", iso.ppm, iso.u_ppm,
      iso.kelvin_steel(), kExpansionSteelPpmPerK, iso.kelvin_aluminium(),
      kExpansionAluminiumPpmPerK);
}

std::string outliers_text(const Diagnosis& d, std::size_t max_listed) {
  if (d.outliers.empty()) return "";
  std::string s = fmt::format(
      "outliers: {} points with a residual beyond {:.3g} µm ({:g} robust σ of the fit), left out "
      "of the fit and the noise estimates:",
      d.outliers.size(), d.outlier_threshold_um, d.outlier_k);
  for (std::size_t i = 0; i < d.outliers.size() && i < max_listed; ++i) {
    const Outlier& o = d.outliers[i];
    s += fmt::format("{} {}{}{} ({:.3f}, {:.3f}, {:.3f}) {:+.2f} µm", i ? ";" : "",
                     o.line ? fmt::format("line {}", o.line) : fmt::format("point {}", o.point + 1),
                     o.set.empty() ? "" : " set ", o.set, o.s.x(), o.s.y(), o.s.z(), o.residual_um);
  }
  if (d.outliers.size() > max_listed)
    s += fmt::format("; … {} more (all in the JSON report)", d.outliers.size() - max_listed);
  return s + "\n";
}

std::string dynamic_text(const Diagnosis& d) {
  if (d.circles.empty()) return "";
  std::string sets;
  for (const auto& c : d.circles) sets += (sets.empty() ? "" : ", ") + c;
  std::string s = fmt::format(
      "circular test ({}): servo mismatch and reversal spikes are dynamic (the drives, not the "
      "geometry) and outside this diagnosis: reported, never named; {}\n",
      sets, d.dynamic.empty() ? "none found" : "found:");
  for (const DynamicFinding& f : d.dynamic) {
    if (f.kind == "servo_mismatch")
      s += fmt::format(
          "  dynamic, not named: servo mismatch in {} (an ellipse at 45° that turns with the "
          "direction of travel, ±{:.3g} µm, {:.1f} σ): unequal gains of the plane's axes\n",
          f.set, f.amplitude_um, f.z);
    else
      s += fmt::format(
          "  dynamic, not named: reversal spikes in {} ({:+.3g} µm within 10° after the "
          "quadrant points, {:.1f} σ)\n",
          f.set, f.amplitude_um, f.z);
  }
  return s;
}

std::string blind_spots_text(const Diagnosis& d) {
  if (d.blind_spots.empty()) return "";
  std::string s = "not testable with these data (the design's blind spots):\n";
  for (const BlindSpot& b : d.blind_spots)
    s += fmt::format("  {}: {}; {}\n", b.what, b.reason, b.measure);
  return s;
}

std::string report_json(const Diagnosis& d) {
  using nlohmann::json;
  json j;
  j["model"] = d.model;
  j["n_points"] = d.n_points;
  j["n_observations"] = d.n_observations;
  j["machine"] = d.machine;
  j["measured"] = d.measured_file;
  j["models"] = json::array();
  for (const ResidualStats& s : d.models)
    j["models"].push_back({{"model", s.model}, {"rms_um", s.rms_um}, {"max_um", s.max_um}});
  j["baseline"] = {{"rms_um", d.baseline.rms_um}, {"max_um", d.baseline.max_um}};
  j["effects"] = json::array();
  for (const SelectedTerm& st : d.effects) {
    const Term& t = st.term;
    json e;
    e["kind"] = kind_id(t.kind);
    e["axis"] = axis_of(t);
    e["direction"] = direction_of(t);
    e["label"] = t.label();
    json params = json::object(), err = json::object();
    for (const auto& [k, v] : t.params()) params[k] = v;
    for (const auto& [k, v] : t.param_stderr()) err[k] = v;
    if (t.kind == TermKind::setup_offset || t.kind == TermKind::setup_rotation) e["set"] = t.set;
    if (t.kind == TermKind::coupling) e["with"] = std::string(1, axis_name(t.with_axis));
    if (t.kind == TermKind::unexplained) {
      e["variables"] = json::array();
      for (int v : t.vars) e["variables"].push_back(variable_name(v));
    }
    e["params"] = params;
    e["stderr"] = err;
    if (const auto [data, tables] = stderr_parts(st); !data.empty()) {
      json ed = json::object(), et = json::object();
      for (const auto& [k, v] : data) ed[k] = v;
      for (const auto& [k, v] : tables) et[k] = v;
      e["stderr_data"] = ed;
      e["stderr_tables"] = et;
    }
    if (!st.linear_parts.empty()) {
      json parts = json::array();
      for (const Term& lp : st.linear_parts) {
        json pp = json::object(), pe = json::object();
        for (const auto& [k, v] : lp.params()) pp[k] = v;
        for (const auto& [k, v] : lp.param_stderr()) pe[k] = v;
        parts.push_back({{"kind", kind_id(lp.kind)},
                         {"axis", axis_of(lp)},
                         {"direction", direction_of(lp)},
                         {"label", lp.label()},
                         {"params", pp},
                         {"stderr", pe}});
      }
      e["linear_part"] = {{"share", st.linear_share}, {"terms", parts}};
    }
    e["explained_fraction"] = st.explained_fraction;
    e["unique_fraction"] = st.unique_fraction;
    e["shared_fraction"] = st.shared_fraction;
    e["description"] = t.description();
    e["ambiguous_with"] = st.ambiguous_with;
    // A cycle named whose period is not resolved: the other periods that
    // fit as well (its status stays "named": kind, axis, direction are).
    if (!st.other_periods_mm.empty()) e["other_periods_mm"] = st.other_periods_mm;
    if (!st.separate_by.empty()) e["separate_by"] = st.separate_by;
    // Not a name: the design cannot tell this effect from its alternatives
    // (ambiguous), or its uncertainty exceeds its value (not_significant).
    e["status"] = status_of(st);
    j["effects"].push_back(e);
  }
  j["datum"] = json::array();
  for (const SelectedTerm& st : d.datum) {
    const Term& t = st.term;
    json e;
    e["kind"] = term_name(t.kind);
    e["set"] = t.set;
    e["axis"] = axis_of(t);
    e["label"] = t.label();
    e["value"] = t.coef.empty() ? 0.0 : t.coef[0];
    e["stderr"] = t.stderr_.empty() ? 0.0 : t.stderr_[0];
    if (!st.stderr_tables.empty()) {
      e["stderr_data"] = st.stderr_data.empty() ? 0.0 : st.stderr_data[0];
      e["stderr_tables"] = st.stderr_tables[0];
    }
    e["explained_fraction"] = st.explained_fraction;
    j["datum"].push_back(e);
  }
  j["explained_together"] = d.explained_together;
  j["extended"] = {
      {"rms_um", d.extended.rms_um},        {"max_um", d.extended.max_um},
      {"holdout_rms_um", d.holdout_rms_um}, {"baseline_holdout_rms_um", d.baseline_holdout_rms_um},
      {"gain_percent", d.gain_percent},     {"folds", d.folds}};
  j["outlier_threshold_um"] = d.outlier_threshold_um;
  j["outliers"] = json::array();
  for (const Outlier& out : d.outliers)
    j["outliers"].push_back({{"line", out.line},
                             {"set", out.set},
                             {"x", out.s.x()},
                             {"y", out.s.y()},
                             {"z", out.s.z()},
                             {"residual_um", out.residual_um}});
  j["circles"] = d.circles;
  j["dynamic"] = json::array();
  for (const DynamicFinding& f : d.dynamic)
    j["dynamic"].push_back(
        {{"kind", f.kind}, {"set", f.set}, {"amplitude_um", f.amplitude_um}, {"z", f.z}});
  j["table_uncertainty_available"] = d.tables.available;
  if (d.tables.draws > 0)
    j["table_uncertainty"] = {
        {"draws", d.tables.draws}, {"seed", d.tables.seed}, {"sources", d.tables.sources}};
  j["noise_um"] = d.noise_um;
  j["noise_independent_um"] = d.noise_independent_um;
  j["noise_method"] = d.noise_method;
  if (d.isotropic.found) {
    json axes = json::array();
    for (int a : d.isotropic.axes) axes.push_back(std::string(1, axis_name(a)));
    j["isotropic_scale"] = {{"axes", axes},
                            {"from_linear_part", d.isotropic.from_linear_part},
                            {"ppm", d.isotropic.ppm},
                            {"u_ppm", d.isotropic.u_ppm},
                            {"chi2", d.isotropic.chi2},
                            {"dof", d.isotropic.axes.size() - 1},
                            {"delta_t_steel_k", d.isotropic.kelvin_steel()},
                            {"delta_t_aluminium_k", d.isotropic.kelvin_aluminium()}};
  }
  if (d.extend_check.done)
    j["extend_check"] = {{"terms", d.extend_check.terms},
                         {"rms_without_um", d.extend_check.rms_without_um},
                         {"rms_with_um", d.extend_check.rms_with_um},
                         {"change_percent", d.extend_check.change_percent()},
                         {"points", d.extend_check.points},
                         {"outside_domain", d.extend_check.outside},
                         {"warnings", d.extend_check.warnings}};
  j["outside_travel_points"] = d.outside_travel_points;
  if (!d.travel_text.empty()) j["travel_warning"] = travel_warning(d);
  j["directions_inferred"] = json::array();
  for (int a : d.directions_inferred)
    j["directions_inferred"].push_back(std::string(1, axis_name(a)));
  j["blind_spots"] = nlohmann::json::array();
  for (const BlindSpot& b : d.blind_spots)
    j["blind_spots"].push_back({{"what", b.what}, {"reason", b.reason}, {"measure", b.measure}});
  j["steps"] = d.log;
  return j.dump(2) + "\n";
}

std::string travel_warning(const Diagnosis& d) {
  if (d.travel_text.empty()) return "";
  return fmt::format(
      "{}: {}: the machine cannot go there, and its tables end at the travel (the model there is "
      "the out-of-range policy's guess); are the data in machine coordinates (not the part's) and "
      "is this the machine they were measured on?",
      d.measured_file, d.travel_text);
}

std::string report_text(const Diagnosis& d) {
  std::string s = fmt::format("{}: {} points ({} observations), machine \"{}\", model {}\n",
                              d.measured_file, d.n_points, d.n_observations, d.machine, d.model);
  if (const std::string w = travel_warning(d); !w.empty()) s += "warning: " + w + "\n";
  if (!d.directions_inferred.empty()) {
    std::string axes;
    for (int a : d.directions_inferred)
      axes += (axes.empty() ? "" : " ") + std::string(1, axis_name(a));
    s += fmt::format(
        "approach directions of {} inferred from the order of the points (the data have none; "
        "--infer-directions)\n",
        axes);
  }
  s += fmt::format("  {:<8} {:>10} {:>10}\n", "model", "rms µm", "max µm");
  for (const ResidualStats& m : d.models)
    s += fmt::format("  {:<8} {:>10.3f} {:>10.3f}\n", m.model, m.rms_um, m.max_um);
  if (!d.datum.empty()) {
    double absorbed = 0.0;
    for (const SelectedTerm& st : d.datum) absorbed += st.explained_fraction;
    s += fmt::format("datum (fitted, not an effect; {:.1f} % of the residual):", 100.0 * absorbed);
    for (const SelectedTerm& st : d.datum)
      s += fmt::format(" [{} {:.3g} ± {:.2g}]", st.term.label(),
                       st.term.coef.empty() ? 0.0 : st.term.coef[0],
                       st.term.stderr_.empty() ? 0.0 : st.term.stderr_[0]);
    s += "\n";
  }
  s += outliers_text(d, 10);
  if (d.effects.empty()) {
    s += "effects: none above the noise floor\n";
  } else {
    s += fmt::format("effects ({}; together {:.1f} % of the residual after the datum):\n",
                     d.effects.size(), 100.0 * d.explained_together);
    if (d.tables.available && d.tables.draws == 0)
      s += "  every u is the data's alone (--table-uncertainty 0): the machine file gives its "
           "tables' uncertainty, and --table-uncertainty N adds it\n";
    if (d.tables.draws > 0)
      s += fmt::format(
          "  every u holds the data's and the tables' uncertainty, √(data² + tables²) ({} draws of "
          "the campaign: {}; --table-uncertainty 0: the data's alone)\n",
          d.tables.draws, d.tables.sources);
    s += fmt::format("  {:<14} {:<4} {:<4} {:>24} {:>9} {:>7} {:>7}  {}\n", "kind", "axis", "dir",
                     "value ± u", "explained", "unique", "shared", "description");
    for (const SelectedTerm& st : d.effects) {
      const Term& t = st.term;
      s += fmt::format("  {:<14} {:<4} {:<4} {:>24} {:>8.1f}% {:>6.1f}% {:>6.1f}%  {}\n",
                       kind_id(t.kind), axis_of(t), direction_of(t), effect_value_text(t),
                       100.0 * st.explained_fraction, 100.0 * st.unique_fraction,
                       100.0 * st.shared_fraction, t.description());
      if (const std::string lp = linear_part_text(st); !lp.empty())
        s += fmt::format("  {:<14} {}\n", "", lp);
      if (const std::string up = uncertainty_parts_text(st); !up.empty())
        s += fmt::format("  {:<14} {}\n", "", up);
      if (!st.significant)
        s += fmt::format(
            "  {:<14} NOT SIGNIFICANT (not a name: its standard uncertainty exceeds its value)\n",
            "");
      if (const std::string pu = period_unresolved_text(st); !pu.empty()) {
        s += fmt::format("  {:<14} NAMED, ITS PERIOD NOT: {}\n", "", pu);
        if (!st.separate_by.empty())
          s += fmt::format("  {:<14} to resolve it: {}\n", "", st.separate_by);
      }
      if (!st.ambiguous_with.empty()) {
        std::string a;
        for (const auto& x : st.ambiguous_with) a += (a.empty() ? "" : "; ") + x;
        s += fmt::format("  {:<14} AMBIGUOUS (not a name: this design cannot tell it from): {}\n",
                         "", a);
        if (!st.separate_by.empty())
          s += fmt::format("  {:<14} to tell them apart: {}\n", "", st.separate_by);
      }
    }
  }
  s += fmt::format(
      "gain: rms {:.3f} → {:.3f} µm in-sample; held-out ({} folds) {:.3f} → {:.3f} µm ({:+.1f} "
      "%); noise σ ≈ {:.3f} µm\n",
      d.baseline.rms_um, d.extended.rms_um, d.folds, d.baseline_holdout_rms_um, d.holdout_rms_um,
      d.gain_percent, d.noise_um);
  s += isotropic_text(d);
  if (d.extend_check.done)
    s += fmt::format(
        "the earlier overlay (--extend, {} term{}) on these data: rms after the datum {:.3f} → "
        "{:.3f} µm ({:+.1f} %)\n",
        d.extend_check.terms, d.extend_check.terms == 1 ? "" : "s", d.extend_check.rms_without_um,
        d.extend_check.rms_with_um, d.extend_check.change_percent());
  s += dynamic_text(d);
  if (d.noise_method != "none" && !d.noise_method.empty())
    s += fmt::format("noise from the data alone ({}): σ ≈ {:.3f} µm\n", d.noise_method,
                     d.noise_independent_um);
  else if (d.noise_method == "none")
    s += "noise from the data alone: not available (no repeated points, no runs of equally "
         "spaced points)\n";
  s += blind_spots_text(d);
  return s;
}

}  // namespace abbe::diagnose
