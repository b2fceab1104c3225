#include "abbe/diagnose/overlay.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "abbe/io/input_error.hpp"
#include "abbe/model/model_kind.hpp"

namespace abbe::diagnose {
namespace {

const char* term_id(TermKind k) {
  switch (k) {
    case TermKind::setup_offset:
      return "setup_offset";
    case TermKind::setup_rotation:
      return "setup_rotation";
    default:
      return kind_id(k);
  }
}

constexpr TermKind kKinds[] = {
    TermKind::model_choice,  TermKind::scale,          TermKind::squareness, TermKind::reversal,
    TermKind::thermal_drift, TermKind::cyclic,         TermKind::coupling,   TermKind::arm_offset,
    TermKind::setup_offset,  TermKind::setup_rotation, TermKind::unexplained};

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void fail(const YAML::Node& n, const std::string& field,
                         const std::string& msg) const {
    const YAML::Mark m = n.Mark();
    throw InputError({file_, m.line >= 0 ? static_cast<std::size_t>(m.line + 1) : 0,
                      m.column >= 0 ? static_cast<std::size_t>(m.column + 1) : 0, field, ""},
                     msg);
  }
  double number(const YAML::Node& n, const std::string& field) const {
    try {
      const double v = n.as<double>();
      if (!std::isfinite(v)) fail(n, field, "not a finite number");
      return v;
    } catch (const YAML::Exception&) {
      fail(n, field, "expected a number");
    }
  }
  int axis(const YAML::Node& n, const std::string& field) const {
    std::string s;
    try {
      s = n.as<std::string>();
    } catch (const YAML::Exception&) {
      fail(n, field, "expected an axis letter X, Y or Z");
    }
    if (s == "X" || s == "x") return 0;
    if (s == "Y" || s == "y") return 1;
    if (s == "Z" || s == "z") return 2;
    fail(n, field, fmt::format("\"{}\" is not an axis (X, Y or Z)", s));
  }
  std::vector<double> numbers(const YAML::Node& n, const std::string& field) const {
    if (!n.IsSequence()) fail(n, field, "expected a list of numbers");
    std::vector<double> v;
    for (const auto& x : n) v.push_back(number(x, field));
    return v;
  }

 private:
  std::string file_;
};

}  // namespace

Eigen::Vector3d Overlay::evaluate(const PointContext& pc) const {
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  for (const Term& t : terms) e += t.evaluate(pc);
  return e;
}

Overlay Overlay::parse(const std::string& text, const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError({file, static_cast<std::size_t>(e.mark.line + 1),
                      static_cast<std::size_t>(e.mark.column + 1), "", ""},
                     e.msg);
  }
  Reader rd(file);
  if (!root.IsMap()) rd.fail(root, "", "an overlay is a YAML mapping (docs/formats.md)");
  if (!root["format"] || root["format"].as<std::string>("") != "abbe-overlay-1")
    rd.fail(root, "format", "missing or unknown `format` (expected abbe-overlay-1)");
  Overlay ov;
  if (root["model"]) ov.base_model = root["model"].as<std::string>("");
  if (!model::parse_model_kind(ov.base_model))
    rd.fail(
        root["model"] ? root["model"] : root, "model",
        fmt::format("unknown model \"{}\" ({})", ov.base_model, model::model_names_text(false)));
  if (root["machine"]) ov.machine = root["machine"].as<std::string>("");
  const YAML::Node effects = root["effects"];
  if (!effects) return ov;
  if (!effects.IsSequence()) rd.fail(effects, "effects", "expected a list of effects");
  for (const YAML::Node& e : effects) {
    if (!e.IsMap()) rd.fail(e, "effects", "each effect is a mapping");
    Term t;
    const YAML::Node term = e["term"] ? e["term"] : e["kind"];
    if (!term) rd.fail(e, "term", "an effect needs `term` (or `kind`)");
    const std::string id = term.as<std::string>("");
    bool found = false;
    for (TermKind k : kKinds)
      if (id == term_id(k)) {
        t.kind = k;
        found = true;
      }
    if (!found) rd.fail(term, "term", fmt::format("unknown effect term \"{}\"", id));
    auto need = [&](const char* key) {
      if (!e[key]) rd.fail(e, key, fmt::format("a {} effect needs `{}`", id, key));
      return e[key];
    };
    const bool needs_axis = t.kind != TermKind::model_choice && t.kind != TermKind::unexplained &&
                            t.kind != TermKind::setup_offset;
    if (needs_axis) t.axis = rd.axis(need("axis"), "axis");
    if (t.kind != TermKind::model_choice && t.kind != TermKind::setup_rotation)
      t.direction = rd.axis(need("direction"), "direction");
    if (t.kind == TermKind::setup_offset) t.axis = t.direction;
    if (t.kind == TermKind::model_choice) t.other_model = need("other_model").as<std::string>("");
    if (t.kind == TermKind::coupling) {
      t.with_axis = rd.axis(need("with"), "with");
      if (t.with_axis == t.axis) rd.fail(e["with"], "with", "coupling needs two different axes");
      const auto c = rd.numbers(need("centre"), "centre");
      const auto h = rd.numbers(need("half"), "half");
      if (c.size() != 3 || h.size() != 3) rd.fail(e, "centre", "centre and half need 3 numbers");
      for (int k = 0; k < 3; ++k) {
        t.centre[k] = c[static_cast<std::size_t>(k)];
        t.half[k] = h[static_cast<std::size_t>(k)];
        if (!(t.half[k] > 0.0)) rd.fail(e["half"], "half", "half ranges must be positive");
      }
    }
    if (t.kind == TermKind::thermal_drift) {
      t.tau_s = rd.number(need("tau_s"), "tau_s");
      if (t.tau_s < 0.0) rd.fail(e["tau_s"], "tau_s", "tau_s must be ≥ 0 (0: linear in t)");
      if (e["with"]) t.with_axis = rd.axis(e["with"], "with");
    }
    if (t.kind == TermKind::cyclic) {
      t.period_mm = rd.number(need("period_mm"), "period_mm");
      if (!(t.period_mm > 0.0)) rd.fail(e["period_mm"], "period_mm", "period must be positive");
    }
    if (t.kind == TermKind::setup_offset || t.kind == TermKind::setup_rotation)
      t.set = need("set").as<std::string>("");
    if (t.kind == TermKind::setup_rotation) {
      const auto c = rd.numbers(need("centre"), "centre");
      if (c.size() != 3) rd.fail(e["centre"], "centre", "centre needs 3 numbers");
      t.centre = Eigen::Vector3d(c[0], c[1], c[2]);
    }
    if (t.kind == TermKind::unexplained) {
      const YAML::Node vars = need("vars");
      if (!vars.IsSequence() || vars.size() < 1 || vars.size() > 2)
        rd.fail(vars, "vars", "vars: one or two of x, y, z, t");
      for (const auto& v : vars) {
        const std::string s = v.as<std::string>("");
        int idx = s == "x" ? 0 : s == "y" ? 1 : s == "z" ? 2 : s == "t" ? 3 : -1;
        if (idx < 0) rd.fail(v, "vars", fmt::format("unknown variable \"{}\"", s));
        t.vars.push_back(idx);
      }
      t.degree = static_cast<int>(rd.number(need("degree"), "degree"));
      if (t.degree < 1 || t.degree > 12) rd.fail(e["degree"], "degree", "degree must be 1..12");
      const auto lo = rd.numbers(need("lo"), "lo"), hi = rd.numbers(need("hi"), "hi");
      if (lo.size() != 4 || hi.size() != 4) rd.fail(e, "lo", "lo and hi need 4 numbers (x y z t)");
      for (std::size_t k = 0; k < 4; ++k) {
        t.lo[k] = lo[k];
        t.hi[k] = hi[k];
        if (!(hi[k] > lo[k])) rd.fail(e["hi"], "hi", "hi must be greater than lo");
      }
    }
    t.coef = rd.numbers(need("coef"), "coef");
    if (static_cast<int>(t.coef.size()) != t.columns())
      rd.fail(
          e["coef"], "coef",
          fmt::format("{} coefficients, {} expected for this term", t.coef.size(), t.columns()));
    if (e["stderr"]) t.stderr_ = rd.numbers(e["stderr"], "stderr");
    ov.terms.push_back(std::move(t));
  }
  return ov;
}

Overlay Overlay::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, 0, 0, "", ""}, "cannot open the overlay file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), path);
}

std::string Overlay::to_yaml() const {
  auto list = [](const auto& v) {
    std::string s = "[";
    for (std::size_t i = 0; i < v.size(); ++i)
      s += fmt::format("{}{:.17g}", i ? ", " : "", static_cast<double>(v[i]));
    return s + "]";
  };
  std::string y = "# abbe machine overlay: effects found by `abbe diagnose` (docs/formats.md)\n";
  y += "format: abbe-overlay-1\n";
  y += fmt::format("model: {}\n", base_model);
  y += fmt::format("machine: \"{}\"\n", machine);
  y += "effects:\n";
  if (terms.empty()) y = y.substr(0, y.size() - 1) + " []\n";
  for (const Term& t : terms) {
    y += fmt::format("  - kind: {}\n    term: {}\n", kind_id(t.kind), term_id(t.kind));
    y += fmt::format("    description: \"{}\"\n", t.description());
    if (t.axis >= 0 && t.kind != TermKind::model_choice && t.kind != TermKind::unexplained)
      y += fmt::format("    axis: {}\n", axis_name(t.axis));
    if (t.direction >= 0) y += fmt::format("    direction: {}\n", axis_name(t.direction));
    if (t.kind == TermKind::model_choice) y += fmt::format("    other_model: {}\n", t.other_model);
    if (t.with_axis >= 0) y += fmt::format("    with: {}\n", axis_name(t.with_axis));
    if (t.kind == TermKind::coupling)
      y += fmt::format("    centre: {}\n    half: {}\n",
                       list(std::array<double, 3>{t.centre[0], t.centre[1], t.centre[2]}),
                       list(std::array<double, 3>{t.half[0], t.half[1], t.half[2]}));
    if (t.kind == TermKind::thermal_drift) y += fmt::format("    tau_s: {:.17g}\n", t.tau_s);
    if (t.kind == TermKind::cyclic) y += fmt::format("    period_mm: {:.17g}\n", t.period_mm);
    if (t.kind == TermKind::setup_offset || t.kind == TermKind::setup_rotation)
      y += fmt::format("    set: \"{}\"\n", t.set);
    if (t.kind == TermKind::setup_rotation)
      y += fmt::format("    centre: {}\n",
                       list(std::array<double, 3>{t.centre[0], t.centre[1], t.centre[2]}));
    if (t.kind == TermKind::unexplained) {
      std::string v;
      for (int x : t.vars) v += std::string(v.empty() ? "" : ", ") + variable_name(x);
      y += fmt::format("    vars: [{}]\n    degree: {}\n    lo: {}\n    hi: {}\n", v, t.degree,
                       list(t.lo), list(t.hi));
    }
    y += fmt::format("    coef: {}\n", list(t.coef));
    if (!t.stderr_.empty()) y += fmt::format("    stderr: {}\n", list(t.stderr_));
  }
  return y;
}

}  // namespace abbe::diagnose
