#include "abbe/diagnose/overlay.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "abbe/diagnose/effect_catalogue.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/model/model_kind.hpp"
#include "src/io/yaml_reader.hpp"

namespace abbe::diagnose {
namespace {

using Reader = io::YamlReader;

int read_axis(const Reader& rd, const YAML::Node& n, const std::string& field) {
  if (!n.IsScalar()) rd.fail(n, field, "expected an axis letter X, Y or Z");
  const std::string s = n.Scalar();
  if (s == "X" || s == "x") return 0;
  if (s == "Y" || s == "y") return 1;
  if (s == "Z" || s == "z") return 2;
  rd.fail(n, field, fmt::format("\"{}\" is not an axis (X, Y or Z)", s));
}

// An overlay entry's fields for the catalogue's readers.
class YamlFields : public OverlayFields {
 public:
  YamlFields(const Reader& rd, const YAML::Node& entry, std::string term)
      : rd_(rd), e_(entry), term_(std::move(term)) {}
  bool has(const char* key) const override { return static_cast<bool>(e_[key]); }
  int axis(const char* key) const override { return read_axis(rd_, need(key), key); }
  double number(const char* key) const override { return rd_.number(need(key), key); }
  std::vector<double> numbers(const char* key) const override {
    return rd_.numbers(need(key), key);
  }
  std::string text(const char* key) const override { return need(key).as<std::string>(""); }
  std::vector<std::string> texts(const char* key) const override {
    const YAML::Node n = need(key);
    std::vector<std::string> out;
    if (n.IsSequence())
      for (const auto& x : n) out.push_back(x.as<std::string>(""));
    return out;
  }
  [[noreturn]] void fail(const char* key, const std::string& message) const override {
    rd_.fail(e_[key] ? e_[key] : e_, key, message);
  }
  [[noreturn]] void fail_entry(const char* key, const std::string& message) const override {
    rd_.fail(e_, key, message);
  }
  [[noreturn]] void fail_item(const char* key, std::size_t index,
                              const std::string& message) const override {
    const YAML::Node n = e_[key];
    rd_.fail(n && n.IsSequence() && index < n.size() ? n[index] : e_, key, message);
  }

 private:
  YAML::Node need(const char* key) const {
    if (!e_[key]) rd_.fail(e_, key, fmt::format("a {} effect needs `{}`", term_, key));
    return e_[key];
  }
  const Reader& rd_;
  const YAML::Node& e_;
  std::string term_;
};

OverlayDomain read_domain(const Reader& rd, const YAML::Node& n) {
  rd.expect_map(n, "domain");
  rd.check_keys(n, "domain", {"min", "max", "time"});
  OverlayDomain d;
  d.known = true;
  d.lo = rd.vec3(rd.required(n, "min", "domain"), "domain.min");
  d.hi = rd.vec3(rd.required(n, "max", "domain"), "domain.max");
  for (int k = 0; k < 3; ++k)
    if (!(d.hi[k] >= d.lo[k]))
      rd.fail(n["max"], "domain.max",
              fmt::format("max {} is below min {} ({})", d.hi[k], d.lo[k], axis_name(k)));
  const YAML::Node time = rd.required(n, "time", "domain");
  const std::vector<double> t = rd.numbers(time, "domain.time", 2);
  if (!(t[1] >= t[0])) rd.fail(time, "domain.time", "the time window ends before it starts");
  d.t_lo = t[0];
  d.t_hi = t[1];
  return d;
}

}  // namespace

Eigen::Vector3d Overlay::evaluate(const PointContext& pc) const {
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  const bool inside = domain.contains(pc, true);
  PointContext clamped;
  if (!inside) clamped = domain.clamp(pc);
  for (const Term& t : terms)
    e += inside || effect_descriptor(t.kind).extrapolates ? t.evaluate(pc) : t.evaluate(clamped);
  return e;
}

bool Overlay::time_dependent() const {
  return std::any_of(terms.begin(), terms.end(), [](const Term& t) {
    return t.kind == TermKind::thermal_drift ||
           (t.kind == TermKind::unexplained &&
            std::find(t.vars.begin(), t.vars.end(), 3) != t.vars.end());
  });
}

Overlay Overlay::parse(const std::string& text, const std::string& file) {
  const Reader rd(file, text);
  const YAML::Node root = rd.load(text);
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
  ov.file = file;
  if (root["domain"]) ov.domain = read_domain(rd, root["domain"]);
  const YAML::Node effects = root["effects"];
  if (!effects) return ov;
  if (!effects.IsSequence()) rd.fail(effects, "effects", "expected a list of effects");
  for (const YAML::Node& e : effects) {
    if (!e.IsMap()) rd.fail(e, "effects", "each effect is a mapping");
    Term t;
    const YAML::Node term = e["term"] ? e["term"] : e["kind"];
    if (!term) rd.fail(e, "term", "an effect needs `term` (or `kind`)");
    const std::string id = term.as<std::string>("");
    const EffectDescriptor* kind = find_effect(id);
    if (!kind) rd.fail(term, "term", fmt::format("unknown effect term \"{}\"", id));
    t.kind = kind->kind;
    const YamlFields fields(rd, e, id);
    if (kind->reads_axis) t.axis = fields.axis("axis");
    if (kind->reads_direction) t.direction = fields.axis("direction");
    if (kind->axis_is_direction) t.axis = t.direction;
    if (kind->read_fields) kind->read_fields(t, fields);
    auto need = [&](const char* key) {
      if (!e[key]) rd.fail(e, key, fmt::format("a {} effect needs `{}`", id, key));
      return e[key];
    };
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
  if (domain.known) {
    const auto v3 = [&](const Eigen::Vector3d& v) {
      return list(std::vector<double>{v[0], v[1], v[2]});
    };
    y += "# fitted on: axis positions s = P + L·e_z (mm) and campaign time (s); outside,\n";
    y += "# polynomial, smooth and time terms are held at their value on the boundary\n";
    y += fmt::format("domain:\n  min: {}\n  max: {}\n  time: {}\n", v3(domain.lo), v3(domain.hi),
                     list(std::vector<double>{domain.t_lo, domain.t_hi}));
  }
  y += "effects:\n";
  if (terms.empty()) y = y.substr(0, y.size() - 1) + " []\n";
  for (const Term& t : terms) {
    const EffectDescriptor& kind = effect_descriptor(t.kind);
    y += fmt::format("  - kind: {}\n    term: {}\n", kind.id, kind.term_name);
    y += fmt::format("    description: \"{}\"\n", t.description());
    if (t.axis >= 0 && kind.writes_axis) y += fmt::format("    axis: {}\n", axis_name(t.axis));
    if (t.direction >= 0) y += fmt::format("    direction: {}\n", axis_name(t.direction));
    if (t.with_axis >= 0) y += fmt::format("    with: {}\n", axis_name(t.with_axis));
    if (kind.write_fields) kind.write_fields(t, y);
    y += fmt::format("    coef: {}\n", list(t.coef));
    if (!t.stderr_.empty()) y += fmt::format("    stderr: {}\n", list(t.stderr_));
  }
  return y;
}

}  // namespace abbe::diagnose
