#include "abbe/diagnose/effect_catalogue.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "effects/builtin_effects.hpp"

namespace abbe::diagnose {
namespace {

std::vector<EffectDescriptor>& registry() {
  static std::vector<EffectDescriptor> rows{
      effects::model_choice(),   effects::scale(),         effects::squareness(),
      effects::reversal(),       effects::thermal_drift(), effects::cyclic(),
      effects::coupling(),       effects::arm_offset(),    effects::setup_offset(),
      effects::setup_rotation(), effects::unexplained()};
  return rows;
}

}  // namespace

const std::vector<EffectDescriptor>& effect_catalogue() { return registry(); }

const EffectDescriptor& effect_descriptor(TermKind kind) {
  const auto& rows = registry();
  const auto i = static_cast<std::size_t>(kind);
  // The built-in kinds are the first rows, in the order of their values.
  if (i < rows.size() && rows[i].kind == kind) return rows[i];
  for (const EffectDescriptor& d : rows)
    if (d.kind == kind) return d;
  throw std::invalid_argument(
      fmt::format("effect kind {} is not in the catalogue", static_cast<int>(kind)));
}

const EffectDescriptor* find_effect(std::string_view term_name) {
  for (const EffectDescriptor& d : registry())
    if (d.term_name == term_name) return &d;
  return nullptr;
}

void register_effect(EffectDescriptor d) {
  if (static_cast<int>(d.kind) < kFirstRegisteredKind)
    throw std::invalid_argument(
        fmt::format("effect \"{}\": a registered kind is ≥ {}", d.term_name, kFirstRegisteredKind));
  for (const EffectDescriptor& row : registry()) {
    if (row.kind == d.kind)
      throw std::invalid_argument(fmt::format("effect \"{}\": kind {} is taken by \"{}\"",
                                              d.term_name, static_cast<int>(d.kind),
                                              row.term_name));
    if (row.term_name == d.term_name)
      throw std::invalid_argument(fmt::format("effect \"{}\": the name is taken", d.term_name));
  }
  if (d.term_name.empty() || d.id.empty())
    throw std::invalid_argument("an effect needs an id and a term name");
  if (!d.basis || !d.label || !d.description || !d.params)
    throw std::invalid_argument(fmt::format(
        "effect \"{}\": basis, label, description and params are required", d.term_name));
  registry().push_back(std::move(d));
}

const char* kind_id(TermKind k) { return effect_descriptor(k).id.c_str(); }
const char* term_name(TermKind k) { return effect_descriptor(k).term_name.c_str(); }

char axis_name(int a) { return a >= 0 && a < 3 ? "XYZ"[a] : '-'; }
const char* variable_name(int v) {
  static const char* kNames[] = {"x", "y", "z", "t"};
  return v >= 0 && v < 4 ? kNames[v] : "?";
}

namespace effects {

std::string yaml_list(const double* values, std::size_t n) {
  std::string s = "[";
  for (std::size_t i = 0; i < n; ++i) s += fmt::format("{}{:.17g}", i ? ", " : "", values[i]);
  return s + "]";
}

Eigen::Vector3d read_point(const OverlayFields& in, const char* key) {
  const std::vector<double> c = in.numbers(key);
  if (c.size() != 3) in.fail(key, fmt::format("{} needs 3 numbers", key));
  return Eigen::Vector3d(c[0], c[1], c[2]);
}

}  // namespace effects
EffectDescriptor make_descriptor(TermKind kind, std::string id, std::string term_name) {
  EffectDescriptor d;
  d.kind = kind;
  d.id = std::move(id);
  d.term_name = std::move(term_name);
  return d;
}

}  // namespace abbe::diagnose
