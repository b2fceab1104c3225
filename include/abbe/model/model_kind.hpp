#pragma once
// The error models as one table (docs/models.md, docs/architecture.md): each
// row names a model, says how its output is written and points to its chain
// formula. The CLI's choices, the reports and diagnosis are built from this
// table, so a new model is one file with its formula plus one row in
// model_table.cpp (or one register_model() call, as the tests do).
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace abbe::model {

// The built-in models; a registered model gets the next free value.
enum class ModelKind : std::uint8_t {
  htm,     // homogeneous transformations, arms from the axis frame origins
  ae_arm,  // first-order vectorial model, arms from the measurement points
  dual,    // the chain over second-order dual numbers, arms from the measurement points
};

struct EvalPoint;
struct Deviation;
class ModelData;
class ModelGeometry;

// The formula of one model: the deviation at `point` (axis positions `s`,
// component errors already looked up into `data.errors`), squareness included.
using ModelFormula = Deviation (*)(const ModelGeometry& geometry, const EvalPoint& point,
                                   const Eigen::Vector3d& s, const ModelData& data);

struct ModelDescriptor {
  ModelKind kind = ModelKind::htm;
  std::string name;           // "ae-arm": CLI, overlays, JSON keys
  std::string column_suffix;  // "ae_arm": CSV column suffix in multi-model output
  std::string description;    // one line for --help and reports
  bool second_order = false;  // the model reports an ε² part (dx2, dy2, dz2 columns)
  bool in_all = true;         // part of `--model all`
  std::string colour;         // report curve colour
  bool dashed = false;        // report curve style
  // The model diagnosis compares against (model_choice effect), by name.
  std::string alternative;
  ModelFormula formula = nullptr;
};

// Every model, built-in first, in table order.
const std::vector<const ModelDescriptor*>& model_table();
const ModelDescriptor& descriptor(ModelKind k);

// Adds a model to the table (at start-up, before any model is built) and
// returns its kind. Throws std::invalid_argument for a taken or empty name
// or a null formula.
ModelKind register_model(ModelDescriptor d);

const char* to_string(ModelKind k);  // the row's name, e.g. "ae-arm"
std::optional<ModelKind> parse_model_kind(std::string_view text);

// "all" (every model with in_all), one name, or a comma-separated list of
// names. Throws abbe::InputError (file "<command line>", field "--model")
// naming the known models.
std::vector<ModelKind> parse_model_list(std::string_view text);

// The model names for a CLI choice, optionally followed by "all".
std::vector<std::string> model_names(bool with_all);
// "htm, ae-arm, dual" (and ", or all" when with_all) for messages and help.
std::string model_names_text(bool with_all);

// The model diagnosis compares `k` with (its row's `alternative`).
ModelKind alternative_model(ModelKind k);

}  // namespace abbe::model
