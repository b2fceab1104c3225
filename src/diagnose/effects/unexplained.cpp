// unexplained: smooth functions of one or two variables (s_x, s_y, s_z, t)
// for what no catalogued effect explains — Legendre products up to `degree`
// per variable over [lo, hi], without the constant.
#include <fmt/format.h>

#include <cmath>

#include "builtin_effects.hpp"

namespace abbe::diagnose::effects {
namespace {

// P_0..P_n of the Legendre polynomials at u.
void legendre(double u, int n, double* out) {
  out[0] = 1.0;
  if (n >= 1) out[1] = u;
  for (int k = 2; k <= n; ++k)
    out[k] = ((2.0 * k - 1.0) * u * out[k - 1] - (k - 1.0) * out[k - 2]) / k;
}

double variable(const PointContext& pc, int v) { return v < 3 ? pc.s[v] : pc.t; }

// (degree+1)^nv multi-indices.
int multi_indices(const Term& t) {
  int n = 1;
  for (std::size_t i = 0; i < t.vars.size(); ++i) n *= t.degree + 1;
  return n;
}

std::string variables(const Term& t, const char* separator) {
  std::string v;
  for (int x : t.vars) v += std::string(v.empty() ? "" : separator) + variable_name(x);
  return v;
}

}  // namespace

EffectDescriptor unexplained() {
  EffectDescriptor d = make_descriptor(TermKind::unexplained, "unexplained", "unexplained");
  d.reads_axis = d.writes_axis = false;
  d.columns = [](const Term& t) { return multi_indices(t) - 1; };
  d.basis = [](const Term& t, const PointContext& pc, BasisOut out) {
    double poly[4][16];
    const std::size_t nv = t.vars.size();
    for (std::size_t i = 0; i < nv; ++i) {
      const auto v = static_cast<std::size_t>(t.vars[i]);
      const double u = 2.0 * (variable(pc, t.vars[i]) - t.lo[v]) / (t.hi[v] - t.lo[v]) - 1.0;
      legendre(u, t.degree, poly[i]);
    }
    // Columns: every multi-index (d_1..d_nv) in [0, degree]^nv except the
    // constant (a setup offset). The linear parts stay: a smooth function
    // must be able to take the whole of an effect outside the catalogue.
    const int n = multi_indices(t);
    Eigen::Index col = 0;
    for (int c = 1; c < n; ++c) {
      int rest = c, total = 0;
      double g = 1.0;
      for (std::size_t i = 0; i < nv; ++i) {
        const int deg = rest % (t.degree + 1);
        total += deg;
        g *= poly[i][deg];
        rest /= t.degree + 1;
      }
      if (total >= 1) out(t.direction, col++) = g;
    }
  };
  d.label = [](const Term& t) {
    return fmt::format("unexplained d{}({})", axis_name(t.direction), variables(t, ","));
  };
  d.description = [](const Term& t) {
    return fmt::format(
        "{} deviation depends smoothly on ({}) in a way no catalogued effect "
        "explains",
        axis_name(t.direction), variables(t, ", "));
  };
  d.params = [](const Term& t) -> NamedValues {
    double ss = 0.0;
    for (double x : t.coef) ss += x * x;
    return {{"columns", static_cast<double>(multi_indices(t) - 1)},
            {"coef_norm_um", std::sqrt(ss)}};
  };
  d.param_stderr = [](const Term&) -> NamedValues { return {}; };
  d.read_fields = [](Term& t, const OverlayFields& in) {
    const std::vector<std::string> vars = in.texts("vars");
    if (vars.size() < 1 || vars.size() > 2) in.fail("vars", "vars: one or two of x, y, z, t");
    for (std::size_t i = 0; i < vars.size(); ++i) {
      const std::string& s = vars[i];
      const int idx = s == "x" ? 0 : s == "y" ? 1 : s == "z" ? 2 : s == "t" ? 3 : -1;
      if (idx < 0) in.fail_item("vars", i, fmt::format("unknown variable \"{}\"", s));
      t.vars.push_back(idx);
    }
    t.degree = static_cast<int>(in.number("degree"));
    if (t.degree < 1 || t.degree > 12) in.fail("degree", "degree must be 1..12");
    const auto lo = in.numbers("lo"), hi = in.numbers("hi");
    if (lo.size() != 4 || hi.size() != 4) in.fail_entry("lo", "lo and hi need 4 numbers (x y z t)");
    for (std::size_t k = 0; k < 4; ++k) {
      t.lo[k] = lo[k];
      t.hi[k] = hi[k];
      if (!(hi[k] > lo[k])) in.fail("hi", "hi must be greater than lo");
    }
  };
  d.write_fields = [](const Term& t, std::string& y) {
    y += fmt::format("    vars: [{}]\n    degree: {}\n    lo: {}\n    hi: {}\n", variables(t, ", "),
                     t.degree, yaml_list(t.lo.data(), 4), yaml_list(t.hi.data(), 4));
  };
  return d;
}

}  // namespace abbe::diagnose::effects
