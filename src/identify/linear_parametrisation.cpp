#include "abbe/identify/linear_parametrisation.hpp"

namespace abbe::identify {

namespace {
// Per parameter: (axis, direction, power) of its components; the second
// entry has axis −1 when the parameter drives one component only.
constexpr std::array<std::array<ParamComponent, 2>, kParamCount> kMap{{
    {{{0, 0, 1}, {-1, 0, 0}}},  // a:  EXX
    {{{1, 1, 1}, {-1, 0, 0}}},  // b:  EYY
    {{{2, 2, 1}, {-1, 0, 0}}},  // c:  EZZ
    {{{0, 4, 1}, {0, 1, 2}}},   // f1: EBX, EYX
    {{{0, 5, 1}, {0, 2, 2}}},   // f2: ECX, EZX
    {{{0, 3, 1}, {-1, 0, 0}}},  // f3: EAX
    {{{1, 3, 1}, {1, 2, 2}}},   // g1: EAY, EZY
    {{{1, 5, 1}, {1, 0, 2}}},   // g2: ECY, EXY
    {{{1, 4, 1}, {-1, 0, 0}}},  // g3: EBY
    {{{2, 3, 1}, {2, 1, 2}}},   // h1: EAZ, EYZ
    {{{2, 4, 1}, {2, 0, 2}}},   // h2: EBZ, EXZ
    {{{2, 5, 1}, {-1, 0, 0}}},  // h3: ECZ
}};
constexpr std::array<const char*, kParamCount> kNames{"a",  "b",  "c",  "f1", "f2", "f3",
                                                      "g1", "g2", "g3", "h1", "h2", "h3"};
}  // namespace

const char* param_name(int i) { return kNames[static_cast<std::size_t>(i)]; }
const char* param_unit(int i) { return i < 3 ? "um/m" : "urad/m"; }

std::array<ParamComponent, 2> param_components(int i, int& count) {
  const auto& m = kMap[static_cast<std::size_t>(i)];
  count = m[1].axis < 0 ? 1 : 2;
  return m;
}

std::array<model::AxisErrors, 3> component_errors(const ParamVector& p, const Eigen::Vector3d& s) {
  std::array<model::AxisErrors, 3> out{};
  for (int i = 0; i < kParamCount; ++i) {
    int n = 0;
    const auto comps = param_components(i, n);
    for (int c = 0; c < n; ++c) {
      const ParamComponent& pc = comps[static_cast<std::size_t>(c)];
      const double q = s[pc.axis];
      // ε = p·s·1e-3 µrad, δ = p·s·1e-3 µm (positioning), δ = p·s²/2·1e-6 µm (straightness).
      const double v = pc.power == 1 ? 1e-3 * p[i] * q : 0.5e-6 * p[i] * q * q;
      model::AxisErrors& e = out[static_cast<std::size_t>(pc.axis)];
      if (pc.d < 3)
        e.delta_um[pc.d] += v;
      else
        e.theta_urad[pc.d - 3] += v;
    }
  }
  return out;
}

}  // namespace abbe::identify
