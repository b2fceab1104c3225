#pragma once
// The three error models (docs/models.md).
#include <cstdint>
#include <optional>
#include <string_view>

namespace abbe::model {

enum class ModelKind : std::uint8_t {
  htm,     // homogeneous transformations, arms from the axis frame origins
  ae_arm,  // first-order vectorial model, arms from the measurement points
  dual,    // the chain over second-order dual numbers, arms from the measurement points
};

const char* to_string(ModelKind k);  // "htm", "ae-arm", "dual"
std::optional<ModelKind> parse_model_kind(std::string_view text);

}  // namespace abbe::model
