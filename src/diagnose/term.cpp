#include "abbe/diagnose/term.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>  // cross()
#include <cmath>

#include "abbe/io/units.hpp"

namespace abbe::diagnose {
namespace {

using units::kTwoPi;

// P_0..P_n of the Legendre polynomials at u.
void legendre(double u, int n, double* out) {
  out[0] = 1.0;
  if (n >= 1) out[1] = u;
  for (int k = 2; k <= n; ++k)
    out[k] = ((2.0 * k - 1.0) * u * out[k - 1] - (k - 1.0) * out[k - 2]) / k;
}

double variable(const PointContext& pc, int v) { return v < 3 ? pc.s[v] : pc.t; }

}  // namespace

const char* kind_id(TermKind k) {
  switch (k) {
    case TermKind::model_choice:
      return "model_choice";
    case TermKind::scale:
      return "scale";
    case TermKind::squareness:
      return "squareness";
    case TermKind::reversal:
      return "reversal";
    case TermKind::thermal_drift:
      return "thermal_drift";
    case TermKind::cyclic:
      return "cyclic";
    case TermKind::coupling:
      return "coupling";
    case TermKind::arm_offset:
      return "arm_offset";
    case TermKind::setup_offset:
    case TermKind::setup_rotation:
      return "setup";
    case TermKind::unexplained:
      return "unexplained";
  }
  return "?";
}

char axis_name(int a) { return a >= 0 && a < 3 ? "XYZ"[a] : '-'; }
const char* variable_name(int v) {
  static const char* kNames[] = {"x", "y", "z", "t"};
  return v >= 0 && v < 4 ? kNames[v] : "?";
}

int Term::columns() const {
  if (kind == TermKind::cyclic) return 2;
  if (kind == TermKind::unexplained) {
    // (degree+1)^nv multi-indices without the constant.
    int n = 1;
    for (std::size_t i = 0; i < vars.size(); ++i) n *= degree + 1;
    return n - 1;
  }
  return 1;
}

void Term::basis(const PointContext& pc,
                 Eigen::Ref<Eigen::Matrix<double, 3, Eigen::Dynamic>> out) const {
  out.setZero();
  switch (kind) {
    case TermKind::model_choice:
      out.col(0) = pc.model_delta_um;
      break;
    case TermKind::scale:
    case TermKind::squareness:
      out(direction, 0) = 1e-3 * pc.s[axis];  // coefficient in µm/m (ppm, µrad)
      break;
    case TermKind::reversal:
      out(direction, 0) = 0.5 * static_cast<double>(pc.dir[static_cast<std::size_t>(axis)]);
      break;
    case TermKind::thermal_drift: {
      const double t = std::max(pc.t, 0.0);
      double f = tau_s > 0.0 ? 1.0 - std::exp(-t / tau_s) : t / 3600.0;
      if (with_axis >= 0) f *= 1e-3 * pc.s[with_axis];
      out(direction, 0) = f;
      break;
    }
    case TermKind::cyclic: {
      const double a = kTwoPi * pc.s[axis] / period_mm;
      out(direction, 0) = std::sin(a);
      out(direction, 1) = std::cos(a);
      break;
    }
    case TermKind::coupling:
      out(direction, 0) = (pc.s[axis] - centre[axis]) / half[axis] *
                          (pc.s[with_axis] - centre[with_axis]) / half[with_axis];
      break;
    case TermKind::arm_offset:  // ε_j × Δ with Δ = e_k (mm): µrad·mm = 1e-3 µm
      out.col(0) = 1e-3 * pc.eps_urad[static_cast<std::size_t>(axis)].cross(
                              Eigen::Vector3d::Unit(direction));
      break;
    case TermKind::setup_offset:
      if (pc.set == set) out(direction, 0) = 1.0;
      break;
    case TermKind::setup_rotation:
      if (pc.set == set) out.col(0) = 1e-3 * Eigen::Vector3d::Unit(axis).cross(pc.p - centre);
      break;
    case TermKind::unexplained: {
      double poly[4][16];
      const std::size_t nv = vars.size();
      for (std::size_t i = 0; i < nv; ++i) {
        const auto v = static_cast<std::size_t>(vars[i]);
        const double u = 2.0 * (variable(pc, vars[i]) - lo[v]) / (hi[v] - lo[v]) - 1.0;
        legendre(u, degree, poly[i]);
      }
      // Columns: every multi-index (d_1..d_nv) in [0, degree]^nv except the
      // constant (a setup offset). The linear parts stay: a smooth function
      // must be able to take the whole of an effect outside the catalogue.
      int n = 1;
      for (std::size_t i = 0; i < nv; ++i) n *= degree + 1;
      Eigen::Index col = 0;
      for (int c = 1; c < n; ++c) {
        int rest = c, total = 0;
        double g = 1.0;
        for (std::size_t i = 0; i < nv; ++i) {
          const int d = rest % (degree + 1);
          total += d;
          g *= poly[i][d];
          rest /= degree + 1;
        }
        if (total >= 1) out(direction, col++) = g;
      }
      break;
    }
  }
}

Eigen::Vector3d Term::evaluate(const PointContext& pc) const {
  Eigen::Matrix<double, 3, Eigen::Dynamic> g(3, columns());
  basis(pc, g);
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  for (int c = 0; c < columns() && c < static_cast<int>(coef.size()); ++c)
    e += coef[static_cast<std::size_t>(c)] * g.col(c);
  return e;
}

std::string Term::label() const {
  const char a = axis_name(axis), d = axis_name(direction);
  switch (kind) {
    case TermKind::model_choice:
      return fmt::format("model_choice ({})", other_model);
    case TermKind::scale:
      return fmt::format("scale {}", a);
    case TermKind::squareness:
      return fmt::format("squareness d{} ∝ {}", d, variable_name(axis));
    case TermKind::reversal:
      return fmt::format("reversal {}→{}", a, d);
    case TermKind::thermal_drift:
      return with_axis >= 0 ? fmt::format("thermal_drift {}·t→{} (τ {:.0f} s)",
                                          variable_name(with_axis), d, tau_s)
                            : fmt::format("thermal_drift t→{} (τ {:.0f} s)", d, tau_s);
    case TermKind::cyclic:
      return fmt::format("cyclic {}→{} ({:.2f} mm)", a, d, period_mm);
    case TermKind::coupling:
      return fmt::format("coupling {}·{}→{}", variable_name(axis), variable_name(with_axis), d);
    case TermKind::arm_offset:
      return fmt::format("arm_offset ε{}×Δ{}", a, d);
    case TermKind::setup_offset:
      return fmt::format("setup offset {} [{}]", d, set);
    case TermKind::setup_rotation:
      return fmt::format("setup rotation about {} [{}]", a, set);
    case TermKind::unexplained: {
      std::string v;
      for (int x : vars) v += std::string(v.empty() ? "" : ",") + variable_name(x);
      return fmt::format("unexplained d{}({})", d, v);
    }
  }
  return "?";
}

std::vector<std::pair<std::string, double>> Term::params() const {
  auto c = [&](std::size_t i) { return i < coef.size() ? coef[i] : 0.0; };
  switch (kind) {
    case TermKind::model_choice:
      return {{"weight", c(0)}};
    case TermKind::scale:
      return {{"ppm", c(0)}};
    case TermKind::squareness:
      return {{"urad", c(0)}};
    case TermKind::reversal:
      return {{"um", c(0)}};
    case TermKind::thermal_drift:
      return {{with_axis >= 0 ? "ppm" : (tau_s > 0.0 ? "um" : "um_per_h"), c(0)}, {"tau_s", tau_s}};
    case TermKind::cyclic: {
      const double amp = std::hypot(c(0), c(1));
      return {
          {"amplitude_um", amp}, {"phase_rad", std::atan2(c(1), c(0))}, {"period_mm", period_mm}};
    }
    case TermKind::coupling:
      return {{"um", c(0)}};
    case TermKind::arm_offset:
      return {{"mm", c(0)}};
    case TermKind::setup_offset:
      return {{"um", c(0)}};
    case TermKind::setup_rotation:
      return {{"urad", c(0)}};
    case TermKind::unexplained: {
      double ss = 0.0;
      for (double x : coef) ss += x * x;
      return {{"columns", static_cast<double>(columns())}, {"coef_norm_um", std::sqrt(ss)}};
    }
  }
  return {};
}

std::vector<std::pair<std::string, double>> Term::param_stderr() const {
  auto s = [&](std::size_t i) { return i < stderr_.size() ? stderr_[i] : 0.0; };
  auto p = params();
  std::vector<std::pair<std::string, double>> out;
  if (kind == TermKind::cyclic) {
    // Amplitude error ≈ the coefficient errors (sin/cos columns are nearly orthogonal).
    out.emplace_back("amplitude_um", std::hypot(s(0), s(1)) / std::sqrt(2.0));
    const double amp = p[0].second;
    out.emplace_back("phase_rad", amp > 0.0 ? std::hypot(s(0), s(1)) / std::sqrt(2.0) / amp : 0.0);
    return out;
  }
  if (kind == TermKind::unexplained) return out;
  out.emplace_back(p[0].first, s(0));
  return out;
}

std::string Term::description() const {
  auto c = [&](std::size_t i) { return i < coef.size() ? coef[i] : 0.0; };
  const char a = axis_name(axis), d = axis_name(direction);
  switch (kind) {
    case TermKind::model_choice:
      return fmt::format(
          "the residual is the difference to the {} model (weight {:.2f}): angular errors are "
          "counted with the wrong arms (Abbe double counting)",
          other_model, c(0));
    case TermKind::scale:
      return fmt::format(
          "{} positions scale by {:+.2f} ppm: thermal expansion or laser "
          "compensation error",
          a, c(0));
    case TermKind::squareness:
      return fmt::format(
          "{} deviation grows with {} by {:+.2f} µrad: axis misalignment "
          "(squareness) drift",
          d, variable_name(axis), c(0));
    case TermKind::reversal:
      return fmt::format("{} jumps by {:+.2f} µm when {} reverses: backlash / lost motion", d, c(0),
                         a);
    case TermKind::thermal_drift:
      return with_axis >= 0 ? fmt::format(
                                  "{} grows with time ∝ {} ({:+.2f} ppm, τ {:.0f} s): thermal "
                                  "expansion during warm-up",
                                  d, variable_name(with_axis), c(0), tau_s)
                            : fmt::format(
                                  "{} drifts with time ({:+.2f} µm, τ {:.0f} s): warm-up, spindle "
                                  "growth",
                                  d, c(0), tau_s);
    case TermKind::cyclic:
      return fmt::format(
          "{} oscillates with {} (period {:.2f} mm, {:.2f} µm): ballscrew pitch "
          "error between table points",
          d, a, period_mm, std::hypot(c(0), c(1)));
    case TermKind::coupling:
      return fmt::format(
          "{} depends on the product of {} and {} ({:+.2f} µm at the travel "
          "corners): sag, bending, non-rigid guideways",
          d, variable_name(axis), variable_name(with_axis), c(0));
    case TermKind::arm_offset:
      return fmt::format(
          "angular errors of {} act with an arm {:+.2f} mm longer along {}: wrong "
          "tool length or reflector position",
          a, c(0), d);
    case TermKind::setup_offset:
      return fmt::format("set {} is shifted by {:+.2f} µm along {}: fixture / part placement", set,
                         c(0), d);
    case TermKind::setup_rotation:
      return fmt::format("set {} is rotated by {:+.2f} µrad about {}: fixture / part placement",
                         set, c(0), a);
    case TermKind::unexplained: {
      std::string v;
      for (int x : vars) v += std::string(v.empty() ? "" : ", ") + variable_name(x);
      return fmt::format(
          "{} deviation depends smoothly on ({}) in a way no catalogued effect "
          "explains",
          d, v);
    }
  }
  return "";
}

}  // namespace abbe::diagnose
