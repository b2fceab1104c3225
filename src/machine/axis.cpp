#include "abbe/machine/axis.hpp"

namespace abbe::machine {

namespace {
constexpr char kDirLetters[kComponentsPerAxis] = {'X', 'Y', 'Z', 'A', 'B', 'C'};
}

char axis_letter(Axis a) { return "XYZ"[index(a)]; }

std::optional<Axis> parse_axis(std::string_view text) {
  if (text == "X") return Axis::x;
  if (text == "Y") return Axis::y;
  if (text == "Z") return Axis::z;
  return std::nullopt;
}

std::string component_name(ComponentId id) {
  return std::string{'E', kDirLetters[id.d], axis_letter(id.axis)};
}

std::optional<ComponentId> parse_component(std::string_view text) {
  if (text.size() != 3 || text[0] != 'E') return std::nullopt;
  auto axis = parse_axis(text.substr(2, 1));
  if (!axis) return std::nullopt;
  for (int d = 0; d < kComponentsPerAxis; ++d)
    if (text[1] == kDirLetters[d]) return ComponentId{*axis, d};
  return std::nullopt;
}

}  // namespace abbe::machine
