// The diagnosis report: JSON with the DESIGN.md §4 keys and the human summary.
#include <fmt/format.h>

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
}  // namespace

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
    e["explained_fraction"] = st.explained_fraction;
    e["description"] = t.description();
    e["ambiguous_with"] = st.ambiguous_with;
    // The design cannot tell this effect from its alternatives: not a name.
    e["status"] = st.ambiguous_with.empty() ? "named" : "ambiguous";
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
    e["explained_fraction"] = st.explained_fraction;
    j["datum"].push_back(e);
  }
  j["extended"] = {
      {"rms_um", d.extended.rms_um},        {"max_um", d.extended.max_um},
      {"holdout_rms_um", d.holdout_rms_um}, {"baseline_holdout_rms_um", d.baseline_holdout_rms_um},
      {"gain_percent", d.gain_percent},     {"folds", d.folds}};
  j["noise_um"] = d.noise_um;
  j["noise_independent_um"] = d.noise_independent_um;
  j["noise_method"] = d.noise_method;
  j["steps"] = d.log;
  return j.dump(2) + "\n";
}

std::string report_text(const Diagnosis& d) {
  std::string s = fmt::format("{}: {} points ({} observations), machine \"{}\", model {}\n",
                              d.measured_file, d.n_points, d.n_observations, d.machine, d.model);
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
  if (d.effects.empty()) {
    s += "effects: none above the noise floor\n";
  } else {
    s += fmt::format("effects ({}):\n", d.effects.size());
    s += fmt::format("  {:<14} {:<4} {:<4} {:>9}  {}\n", "kind", "axis", "dir", "explained",
                     "description");
    for (const SelectedTerm& st : d.effects) {
      const Term& t = st.term;
      s += fmt::format("  {:<14} {:<4} {:<4} {:>8.1f}%  {}\n", kind_id(t.kind), axis_of(t),
                       direction_of(t), 100.0 * st.explained_fraction, t.description());
      if (!st.ambiguous_with.empty()) {
        std::string a;
        for (const auto& x : st.ambiguous_with) a += (a.empty() ? "" : "; ") + x;
        s += fmt::format("  {:<14} AMBIGUOUS (not a name: this design cannot tell it from): {}\n",
                         "", a);
      }
    }
  }
  s += fmt::format(
      "gain: rms {:.3f} → {:.3f} µm in-sample; held-out ({} folds) {:.3f} → {:.3f} µm ({:+.1f} "
      "%); noise σ ≈ {:.3f} µm\n",
      d.baseline.rms_um, d.extended.rms_um, d.folds, d.baseline_holdout_rms_um, d.holdout_rms_um,
      d.gain_percent, d.noise_um);
  if (d.noise_method != "none" && !d.noise_method.empty())
    s += fmt::format("noise from the data alone ({}): σ ≈ {:.3f} µm\n", d.noise_method,
                     d.noise_independent_um);
  return s;
}

}  // namespace abbe::diagnose
