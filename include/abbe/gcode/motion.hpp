#pragma once
// Motion: what the interpreter hands on, one per rapid, feed, arc or dwell.
// All positions are tool-tip positions P in machine coordinates, mm
// (DESIGN.md §2): program point + work offset + G92 offset; s = P + L·e_z.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>

namespace abbe::gcode {

enum class MotionKind : std::uint8_t { rapid, linear, arc, dwell };

const char* to_string(MotionKind kind);

// Plane of an arc, named by its normal axis: XY (G17, normal Z), XZ (G18,
// normal Y), YZ (G19, normal X).
enum class Plane : std::uint8_t { xy, xz, yz };

// Indices of a plane's (first, second, normal) axes in LinuxCNC's order:
// G17 XY (0, 1, 2), G18 ZX (2, 0, 1), G19 YZ (1, 2, 0), so that positive
// angles turn counter-clockwise seen from the normal's positive side.
inline std::array<int, 3> plane_axes(Plane plane) {
  switch (plane) {
    case Plane::xz:
      return {2, 0, 1};
    case Plane::yz:
      return {1, 2, 0};
    case Plane::xy:
      break;
  }
  return {0, 1, 2};
}

struct Motion {
  MotionKind kind = MotionKind::rapid;
  std::size_t line = 0;   // source line (1-based)
  std::uint32_t sub = 0;  // index of this motion among those of its block (canned cycles)
  // Tool tip, machine coordinates, mm. `start` is the tip with this motion's
  // tool length: after a tool length change (G43/G49) without a move it
  // differs from the previous motion's end by the length change (the
  // spindle s did not move). Dwells have start == end.
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  double tool_length = 0.0;    // active L, mm (s = P + L·e_z)
  double feed = 0.0;           // mm/min (0 for rapids: the rapid rate applies)
  double dwell_seconds = 0.0;  // for kind == dwell

  // Arc (kind == arc) — LinuxCNC's canonical form:
  Plane plane = Plane::xy;
  Eigen::Vector3d center =
      Eigen::Vector3d::Zero();  // centre; its normal-axis coordinate equals start's
  // rotation > 0: counter-clockwise seen from the + end of the normal axis
  // (G3 in G17), < 0: clockwise; |rotation| - 1 = extra full turns (P word).
  // The plane's (first, second) axes are XY: (X, Y), XZ (G18): (Z, X),
  // YZ (G19): (Y, Z), so G3 in G18 turns from +Z towards +X. When start and
  // end coincide in the plane, |rotation| = 1 is one full circle. `end` is
  // the programmed end point (within LinuxCNC's radius tolerance of the
  // circle); the normal-axis coordinate moves linearly (helix).
  int rotation = 0;

  // What is carried along from the block (not used for geometry).
  double spindle = 0.0;  // S
  int tool = 0;          // T (selected tool)
};

}  // namespace abbe::gcode
