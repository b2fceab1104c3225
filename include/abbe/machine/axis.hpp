#pragma once
// Axis and component names (ISO 230-1): axis j ∈ {X, Y, Z}; component
// E<d><j> with d ∈ {X, Y, Z} (linear, µm) or {A, B, C} (angular, µrad).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace abbe::machine {

enum class Axis : std::uint8_t { x = 0, y = 1, z = 2 };
constexpr std::array<Axis, 3> kAxes{Axis::x, Axis::y, Axis::z};

constexpr int index(Axis a) { return static_cast<int>(a); }
char axis_letter(Axis a);                               // 'X', 'Y', 'Z'
std::optional<Axis> parse_axis(std::string_view text);  // "X", "Y", "Z" (upper case)

// The six components of one axis, in the order used everywhere: the linear
// errors along X, Y, Z, then the rotations about X, Y, Z.
constexpr int kComponentsPerAxis = 6;

struct ComponentId {
  Axis axis = Axis::x;
  int d = 0;  // 0..5: EX·, EY·, EZ·, EA·, EB·, EC·
  bool linear() const { return d < 3; }
};

std::string component_name(ComponentId id);  // e.g. "EYX"
// Parses "E<d><j>"; nullopt when it is not an axis component name (squareness
// names such as EC0Y are not components of the table).
std::optional<ComponentId> parse_component(std::string_view text);

}  // namespace abbe::machine
