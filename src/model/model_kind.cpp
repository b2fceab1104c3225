#include "abbe/model/model_kind.hpp"

namespace abbe::model {

const char* to_string(ModelKind k) {
  switch (k) {
    case ModelKind::htm:
      return "htm";
    case ModelKind::ae_arm:
      return "ae-arm";
    case ModelKind::dual:
      return "dual";
  }
  return "?";
}

std::optional<ModelKind> parse_model_kind(std::string_view text) {
  if (text == "htm") return ModelKind::htm;
  if (text == "ae-arm") return ModelKind::ae_arm;
  if (text == "dual") return ModelKind::dual;
  return std::nullopt;
}

}  // namespace abbe::model
