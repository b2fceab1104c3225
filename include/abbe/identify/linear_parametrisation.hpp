#pragma once
// The linear parametrisation of the dual-number paper (section 4): twelve
// parameters describe all 18 component errors of a 3-axis machine,
//   positioning   EXX = a·s_x,  EYY = b·s_y,  EZZ = c·s_z,
//   X: EBX = f1·s_x, ECX = f2·s_x, EAX = f3·s_x, EYX = f1·s_x²/2, EZX = f2·s_x²/2,
//   Y: EAY = g1·s_y, ECY = g2·s_y, EBY = g3·s_y, EZY = g1·s_y²/2, EXY = g2·s_y²/2,
//   Z: EAZ = h1·s_z, EBZ = h2·s_z, ECZ = h3·s_z, EYZ = h1·s_z²/2, EXZ = h2·s_z²/2,
// i.e. the paper's δ_xx = a x, δ_yx = f1 x²/2, ε_yx = f1 x, … with ε_{dj} the
// rotation of axis j about d. A straightness that is the integral of an
// angular error shares its parameter; the rolls (f3, g3 for EBY, h3 for ECZ)
// have no straightness partner. Positions are the axis positions s (mm).
//
// Units: a, b, c in µm/m (ppm); f, g, h in µrad/m. Then
//   δ = a·s·1e-3 µm, ε = f·s·1e-3 µrad, δ = f·s²/2·1e-6 µm
// (the straightness is the integral of ε: δ[mm] = ∫ ε[rad] ds[mm]).
#include <Eigen/Core>
#include <array>
#include <string>

#include "abbe/model/axis_error_table.hpp"

namespace abbe::identify {

enum class Param : int { a = 0, b, c, f1, f2, f3, g1, g2, g3, h1, h2, h3 };
constexpr int kParamCount = 12;
using ParamVector = Eigen::Matrix<double, kParamCount, 1>;

const char* param_name(int i);  // "a", "b", …, "h3"
const char* param_unit(int i);  // "um/m" or "urad/m"

// Which component (axis, ISO direction 0..5) a parameter drives and how:
// `power` 1 → value = scale·p·s, power 2 → value = scale·p·s²/2.
struct ParamComponent {
  int axis;  // 0 X, 1 Y, 2 Z
  int d;     // 0..2 linear EX·/EY·/EZ·, 3..5 angular EA·/EB·/EC·
  int power;
};
// The one or two components of parameter i.
std::array<ParamComponent, 2> param_components(int i, int& count);

// The component errors of the three axes at axis positions s for parameters p.
std::array<model::AxisErrors, 3> component_errors(const ParamVector& p, const Eigen::Vector3d& s);

}  // namespace abbe::identify
