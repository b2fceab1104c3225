#include "abbe/identify/table_fit.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>

#include "abbe/identify/workspace_map.hpp"

namespace abbe::identify {

namespace {

// Hat-function weights of s on the knots: (index of the left knot, weight of the right).
void hat(const std::vector<double>& knots, double s, std::size_t& left, double& w) {
  if (knots.size() == 1 || s <= knots.front()) {
    left = 0;
    w = 0.0;
    return;
  }
  if (s >= knots.back()) {
    left = knots.size() - 2;
    w = 1.0;
    return;
  }
  left =
      static_cast<std::size_t>(std::upper_bound(knots.begin(), knots.end(), s) - knots.begin()) - 1;
  w = (s - knots[left]) / (knots[left + 1] - knots[left]);
}

}  // namespace

TableFit fit_component_tables(const ChainExpansion& chain, const std::vector<Observation>& data,
                              const TableFitOptions& options) {
  TableFit out;
  // Knots over the range of s_j the data cover.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const Observation& o : data) {
    const Eigen::Vector3d s = o.point.p + Eigen::Vector3d(0.0, 0.0, o.point.tool_length);
    lo = lo.cwiseMin(s);
    hi = hi.cwiseMax(s);
  }
  std::array<std::vector<double>, 3> knots;
  std::array<int, 19> offset{};  // first unknown of component c = 6·axis + d
  int n = 0;
  for (int a = 0; a < 3; ++a) {
    knots[static_cast<std::size_t>(a)] =
        data.empty() ? std::vector<double>{0.0} : grid_axis(lo[a], hi[a], options.knot_spacing_mm);
    for (int d = 0; d < 6; ++d) {
      offset[static_cast<std::size_t>(6 * a + d)] = n;
      n += static_cast<int>(knots[static_cast<std::size_t>(a)].size());
    }
  }
  offset[18] = n;
  out.unknowns = n;

  long m = 0;
  for (const Observation& o : data)
    for (bool h : o.has) m += h ? 1 : 0;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m, n);
  Eigen::VectorXd b(m);
  Eigen::Index row = 0;
  Eigen::Vector3d first, second;
  for (const Observation& o : data) {
    const Eigen::Vector3d s = o.point.p + Eigen::Vector3d(0.0, 0.0, o.point.tool_length);
    // Response of the chain (ε part) to a unit error of each component.
    Eigen::Matrix<double, 3, 18> sens;
    for (int c = 0; c < 18; ++c) {
      std::array<model::AxisErrors, 3> e{};
      auto& ax = e[static_cast<std::size_t>(c / 6)];
      if (c % 6 < 3)
        ax.delta_um[c % 6] = 1.0;
      else
        ax.theta_urad[c % 6 - 3] = 1.0;
      chain.evaluate(o.point, e, first, second);
      sens.col(c) = first;
    }
    const Eigen::Vector3d rhs = o.d_um - chain.squareness_um(o.point.p);
    for (int k = 0; k < 3; ++k) {
      if (!o.has[static_cast<std::size_t>(k)]) continue;
      for (int c = 0; c < 18; ++c) {
        const int ax = c / 6;
        std::size_t left = 0;
        double w = 0.0;
        hat(knots[static_cast<std::size_t>(ax)], s[ax], left, w);
        const int col = offset[static_cast<std::size_t>(c)] + static_cast<int>(left);
        a(row, col) += (1.0 - w) * sens(k, c);
        if (knots[static_cast<std::size_t>(ax)].size() > 1) a(row, col + 1) += w * sens(k, c);
      }
      b[row] = rhs[k];
      ++row;
    }
  }
  out.n_values = static_cast<std::size_t>(m);

  // Unit-norm columns, so the null space speaks in comparable units.
  Eigen::VectorXd scale = a.colwise().norm().transpose();
  for (Eigen::Index j = 0; j < n; ++j)
    if (!(scale[j] > 0.0)) scale[j] = 1.0;
  const Eigen::MatrixXd as = a * scale.cwiseInverse().asDiagonal();
  out.fit = solve_least_squares(as, b, options.least_squares);

  auto component_of = [&](Eigen::Index j) {
    int c = 0;
    while (offset[static_cast<std::size_t>(c + 1)] <= j) ++c;
    return c;
  };
  auto name_of = [](int c) {
    return machine::component_name({machine::kAxes[static_cast<std::size_t>(c / 6)], c % 6});
  };
  // Separability per component, basis-free: with N the orthonormal null
  // space (scaled unknowns), the block N_c·N_cᵀ of component c has
  // eigenvalues in [0, 1]; each one above 10⁻³ is a shape of c (a knot
  // combination) that some unidentifiable direction contains: the data
  // cannot tell it from other components (or, at 1, cannot see it at all).
  Eigen::MatrixXd null(n, static_cast<Eigen::Index>(out.fit.null_space.size()));
  for (std::size_t i = 0; i < out.fit.null_space.size(); ++i)
    null.col(static_cast<Eigen::Index>(i)) = out.fit.null_space[i].direction;  // unit-norm columns
  if (null.cols() > 0) {
    // Orthonormalise (the solver's own rescaling may bend the basis slightly).
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(null);
    null = qr.householderQ() * Eigen::MatrixXd::Identity(n, null.cols());
  }
  for (int c = 0; c < 18; ++c) {
    ComponentSeparability sc;
    sc.id = {machine::kAxes[static_cast<std::size_t>(c / 6)], c % 6};
    const int o0 = offset[static_cast<std::size_t>(c)];
    const int nc = offset[static_cast<std::size_t>(c + 1)] - o0;
    sc.knots = nc;
    if (null.cols() > 0 && nc > 0) {
      const Eigen::MatrixXd nb = null.middleRows(o0, nc);
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(nb * nb.transpose());
      std::array<double, 18> partner{};
      for (Eigen::Index e = 0; e < nc; ++e) {
        const double lambda = es.eigenvalues()[e];
        sc.null_share = std::max(sc.null_share, lambda);
        if (lambda > 1e-3) ++sc.null_dims;
        if (lambda < 0.05) continue;
        // The null vector closest to this shape of c: where else it lives.
        Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
        u.segment(o0, nc) = es.eigenvectors().col(e);
        const Eigen::VectorXd v = null * (null.transpose() * u);
        const double vn = v.squaredNorm();
        for (int o = 0; o < 18; ++o) {
          if (o == c) continue;
          const int p0 = offset[static_cast<std::size_t>(o)];
          const int np = offset[static_cast<std::size_t>(o + 1)] - p0;
          partner[static_cast<std::size_t>(o)] =
              std::max(partner[static_cast<std::size_t>(o)], v.segment(p0, np).squaredNorm() / vn);
        }
      }
      for (int o = 0; o < 18; ++o)
        if (partner[static_cast<std::size_t>(o)] > 0.1) sc.confounded_with.push_back(name_of(o));
    }
    out.separability.push_back(sc);
  }
  for (const NullDirection& nd : out.fit.null_space)
    out.unidentifiable.push_back(describe_combination(
        nd.direction.cwiseQuotient(scale).normalized(),
        [&] {
          std::vector<std::string> names;
          for (Eigen::Index j = 0; j < n; ++j) {
            const int c = component_of(j);
            names.push_back(fmt::format(
                "{}@{:g}", name_of(c),
                knots[static_cast<std::size_t>(c / 6)]
                     [static_cast<std::size_t>(j - offset[static_cast<std::size_t>(c)])]));
          }
          return names;
        }(),
        0.2));

  // Gauge: angular columns weighted 10⁻³ in the minimum-norm choice.
  Eigen::VectorXd gauge = Eigen::VectorXd::Ones(n);
  for (Eigen::Index j = 0; j < n; ++j)
    if (component_of(j) % 6 >= 3) gauge[j] = 1e-3;
  const LeastSquaresResult gfit =
      solve_least_squares(as * gauge.asDiagonal(), b, options.least_squares);
  const Eigen::VectorXd x = gauge.cwiseProduct(gfit.x).cwiseQuotient(scale);
  const Eigen::VectorXd res = b - a * x;
  out.residual_rms_um = m > 0 ? std::sqrt(res.squaredNorm() / static_cast<double>(m)) : 0.0;
  out.residual_max_um = m > 0 ? res.cwiseAbs().maxCoeff() : 0.0;
  for (int c = 0; c < 18; ++c) {
    FittedSeries fs;
    fs.id = {machine::kAxes[static_cast<std::size_t>(c / 6)], c % 6};
    fs.knots_mm = knots[static_cast<std::size_t>(c / 6)];
    for (int i = offset[static_cast<std::size_t>(c)]; i < offset[static_cast<std::size_t>(c + 1)];
         ++i) {
      fs.value.push_back(x[i]);
      fs.stderr_value.push_back(out.fit.stderr_x[i] / scale[i]);
    }
    out.series.push_back(std::move(fs));
  }
  return out;
}

std::string table_fit_to_csv(const TableFit& fit) {
  std::string out = "axis,component,position_mm,direction,value\n";
  for (const FittedSeries& s : fit.series) {
    if (s.knots_mm.size() < 2) continue;  // a single position makes no table
    const std::string name = machine::component_name(s.id);
    for (std::size_t i = 0; i < s.knots_mm.size(); ++i)
      out += fmt::format("{},{},{:.6g},mean,{:.6g}\n", machine::axis_letter(s.id.axis), name,
                         s.knots_mm[i], s.value[i]);
  }
  return out;
}

}  // namespace abbe::identify
