// The model table: one row per error model (model_kind.hpp).
#include <fmt/format.h>

#include <deque>
#include <mutex>
#include <stdexcept>

#include "abbe/io/input_error.hpp"
#include "abbe/model/model_kind.hpp"
#include "ae_arm_model_inl.hpp"
#include "model_formulas.hpp"

namespace abbe::model {

Deviation evaluate_ae_arm(const ModelGeometry& geometry, const EvalPoint& point,
                          const Eigen::Vector3d& s, const ModelData& data) {
  return evaluate_ae_arm_inline(geometry, point, s, data);
}

namespace {

struct Table {
  std::deque<ModelDescriptor> rows;  // stable addresses
  std::vector<const ModelDescriptor*> view;
  Table() {
    add({ModelKind::htm, "htm", "htm",
         "homogeneous transformations, arms from the axis frame origins", false, true, "#d62728",
         false, "ae-arm", &evaluate_htm});
    add({ModelKind::ae_arm, "ae-arm", "ae_arm",
         "Abbe-corrected first-order model, arms from the measurement points", false, true,
         "#1f77b4", false, "htm", &evaluate_ae_arm});
    add({ModelKind::dual, "dual", "dual",
         "the chain over second-order dual numbers (first order = ae-arm)", true, true, "#2ca02c",
         true, "htm", &evaluate_dual});
  }
  void add(ModelDescriptor d) {
    rows.push_back(std::move(d));
    view.push_back(&rows.back());
  }
};

Table& table() {
  static Table t;
  return t;
}

}  // namespace

const std::vector<const ModelDescriptor*>& model_table() { return table().view; }

const ModelDescriptor& descriptor(ModelKind k) {
  const auto& v = table().view;
  const auto i = static_cast<std::size_t>(k);
  if (i >= v.size()) throw std::out_of_range(fmt::format("no error model with kind {}", i));
  return *v[i];
}

ModelKind register_model(ModelDescriptor d) {
  static std::mutex m;
  std::lock_guard<std::mutex> lock(m);
  Table& t = table();
  if (d.name.empty() || d.name == "all" || !d.formula)
    throw std::invalid_argument("register_model: a model needs a name (not \"all\") and a formula");
  if (parse_model_kind(d.name))
    throw std::invalid_argument(fmt::format("register_model: \"{}\" is taken", d.name));
  if (t.rows.size() > 255) throw std::invalid_argument("register_model: too many models");
  d.kind = static_cast<ModelKind>(t.rows.size());
  if (d.column_suffix.empty()) d.column_suffix = d.name;
  t.add(std::move(d));
  return t.view.back()->kind;
}

const char* to_string(ModelKind k) {
  const auto& v = table().view;
  const auto i = static_cast<std::size_t>(k);
  return i < v.size() ? v[i]->name.c_str() : "?";
}

std::optional<ModelKind> parse_model_kind(std::string_view text) {
  for (const ModelDescriptor* d : table().view)
    if (d->name == text) return d->kind;
  return std::nullopt;
}

std::vector<std::string> model_names(bool with_all) {
  std::vector<std::string> names;
  for (const ModelDescriptor* d : table().view) names.push_back(d->name);
  if (with_all) names.emplace_back("all");
  return names;
}

std::string model_names_text(bool with_all) {
  const auto names = model_names(false);
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i)
    s += (i == 0 ? "" : (i + 1 == names.size() && !with_all) ? " or " : ", ") + names[i];
  if (with_all) s += " or all";
  return s;
}

std::vector<ModelKind> parse_model_list(std::string_view text) {
  std::vector<ModelKind> kinds;
  if (text == "all") {
    for (const ModelDescriptor* d : table().view)
      if (d->in_all) kinds.push_back(d->kind);
    return kinds;
  }
  std::size_t begin = 0;
  while (begin <= text.size()) {
    std::size_t end = text.find(',', begin);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view name = text.substr(begin, end - begin);
    const auto k = parse_model_kind(name);
    if (!k)
      throw InputError({"<command line>", 0, 0, "--model", ""},
                       fmt::format("unknown model \"{}\" ({})", name, model_names_text(true)));
    for (ModelKind seen : kinds)
      if (seen == *k)
        throw InputError({"<command line>", 0, 0, "--model", ""},
                         fmt::format("model \"{}\" is named twice", name));
    kinds.push_back(*k);
    begin = end + 1;
  }
  return kinds;
}

ModelKind alternative_model(ModelKind k) {
  return parse_model_kind(descriptor(k).alternative).value_or(ModelKind::htm);
}

}  // namespace abbe::model
