#include "abbe/identify/parameter_identification.hpp"

#include <Eigen/QR>
#include <cmath>

namespace abbe::identify {

namespace {

struct Design {
  std::vector<MonomialRows> rows;  // per observation
  std::vector<Eigen::Vector3d> rhs;
};

Design build_design(const ChainExpansion& chain, const std::vector<Observation>& data) {
  Design d;
  d.rows.reserve(data.size());
  d.rhs.reserve(data.size());
  for (const Observation& o : data) {
    d.rows.push_back(chain.monomials(o.point));
    d.rhs.push_back(o.d_um - chain.squareness_um(o.point.p));
  }
  return d;
}

// Least squares for the monomials that are non-zero on the chosen components.
MonomialFit fit_monomials(const Design& d, const std::vector<Observation>& data,
                          const std::array<bool, 3>& components, const LeastSquaresOptions& opt) {
  std::array<bool, kMonomialCount> used{};
  long m = 0;
  for (std::size_t r = 0; r < data.size(); ++r)
    for (int k = 0; k < 3; ++k) {
      if (!components[static_cast<std::size_t>(k)] || !data[r].has[static_cast<std::size_t>(k)])
        continue;
      ++m;
      for (int c = 0; c < kMonomialCount; ++c)
        if (d.rows[r](k, c) != 0.0) used[static_cast<std::size_t>(c)] = true;
    }
  MonomialFit out;
  for (int c = 0; c < kMonomialCount; ++c)
    if (used[static_cast<std::size_t>(c)]) out.monomials.push_back(c);
  const auto n = static_cast<Eigen::Index>(out.monomials.size());
  Eigen::MatrixXd a(m, n);
  Eigen::VectorXd b(m);
  Eigen::Index row = 0;
  for (std::size_t r = 0; r < data.size(); ++r)
    for (int k = 0; k < 3; ++k) {
      if (!components[static_cast<std::size_t>(k)] || !data[r].has[static_cast<std::size_t>(k)])
        continue;
      for (Eigen::Index c = 0; c < n; ++c)
        a(row, c) = d.rows[r](k, out.monomials[static_cast<std::size_t>(c)]);
      b[row] = d.rhs[r][k];
      ++row;
    }
  out.fit = solve_least_squares(a, b, opt);
  return out;
}

// Residual and Jacobian of the exact quadratic model at p (observed values only).
void linearise(const Design& d, const std::vector<Observation>& data, const ParamVector& p,
               Eigen::MatrixXd& jac, Eigen::VectorXd& res) {
  const Eigen::Matrix<double, kMonomialCount, 1> mv = ChainExpansion::monomial_values(p);
  // ∂(p_i p_j)/∂p_l as a 90 × 12 matrix.
  Eigen::Matrix<double, kMonomialCount, kParamCount> dm =
      Eigen::Matrix<double, kMonomialCount, kParamCount>::Zero();
  for (int i = 0; i < kParamCount; ++i) {
    dm(i, i) = 1.0;
    for (int j = i; j < kParamCount; ++j) {
      const int k = product_index(i, j);
      dm(k, i) += p[j];
      dm(k, j) += p[i];
    }
  }
  long m = 0;
  for (const Observation& o : data)
    for (bool h : o.has) m += h ? 1 : 0;
  jac.resize(m, kParamCount);
  res.resize(m);
  Eigen::Index row = 0;
  for (std::size_t r = 0; r < data.size(); ++r)
    for (int k = 0; k < 3; ++k) {
      if (!data[r].has[static_cast<std::size_t>(k)]) continue;
      jac.row(row) = d.rows[r].row(k) * dm;
      res[row] = d.rhs[r][k] - d.rows[r].row(k).dot(mv.transpose());
      ++row;
    }
}

}  // namespace

std::vector<std::string> param_names() {
  std::vector<std::string> n;
  for (int i = 0; i < kParamCount; ++i) n.emplace_back(param_name(i));
  return n;
}

std::vector<std::string> monomial_names(const std::vector<int>& monomials) {
  std::vector<std::string> n;
  for (int k : monomials) n.push_back(monomial_name(k));
  return n;
}

ParamIdentification identify_linear(const ChainExpansion& chain,
                                    const std::vector<Observation>& data,
                                    const IdentifyOptions& options) {
  ParamIdentification out;
  const Design d = build_design(chain, data);
  out.n_points = data.size();
  for (int k = 0; k < 3; ++k) {
    std::array<bool, 3> only{false, false, false};
    only[static_cast<std::size_t>(k)] = true;
    out.per_component[static_cast<std::size_t>(k)] =
        fit_monomials(d, data, only, options.least_squares);
  }
  out.joint = fit_monomials(d, data, {true, true, true}, options.least_squares);

  // Start: the linear monomials of the joint fit.
  ParamVector p = ParamVector::Zero();
  for (std::size_t c = 0; c < out.joint.monomials.size(); ++c)
    if (out.joint.monomials[c] < kParamCount)
      p[out.joint.monomials[c]] = out.joint.fit.x[static_cast<Eigen::Index>(c)];

  // Gauss–Newton on the quadratic model; the steps are minimum-norm in the
  // unidentifiable directions, so those stay where the start put them.
  Eigen::MatrixXd jac;
  Eigen::VectorXd res;
  for (int it = 0; it < options.max_iterations; ++it) {
    linearise(d, data, p, jac, res);
    LeastSquaresResult step = solve_least_squares(jac, res, options.least_squares);
    p += step.x;
    out.iterations = it + 1;
    if (step.x.norm() <= 1e-13 * std::max(1.0, p.norm())) break;
  }
  // Along unidentifiable combinations the start is arbitrary (the monomial
  // fit's choice): take the minimum-norm parameters there, then settle again.
  linearise(d, data, p, jac, res);
  const LeastSquaresResult probe = solve_least_squares(jac, res, options.least_squares);
  if (!probe.null_space.empty()) {
    Eigen::MatrixXd nd(kParamCount, static_cast<Eigen::Index>(probe.null_space.size()));
    for (std::size_t c = 0; c < probe.null_space.size(); ++c)
      nd.col(static_cast<Eigen::Index>(c)) = probe.null_space[c].direction;
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(nd);
    const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(kParamCount, nd.cols());
    p -= q * (q.transpose() * p);
    for (int it = 0; it < options.max_iterations; ++it) {
      linearise(d, data, p, jac, res);
      const LeastSquaresResult step = solve_least_squares(jac, res, options.least_squares);
      p += step.x;
      if (step.x.norm() <= 1e-13 * std::max(1.0, p.norm())) break;
    }
  }
  linearise(d, data, p, jac, res);
  // The statistics of the last linearisation: the step is zero there, so its
  // residual is the model residual.
  out.final_fit = solve_least_squares(jac, res, options.least_squares);
  out.n_values = static_cast<std::size_t>(res.size());
  out.p = p;
  out.residual_rms_um =
      out.final_fit.rows > 0 ? std::sqrt(res.squaredNorm() / static_cast<double>(res.size())) : 0.0;
  out.residual_max_um = res.size() > 0 ? res.cwiseAbs().maxCoeff() : 0.0;
  for (int i = 0; i < kParamCount; ++i) {
    out.identifiable[static_cast<std::size_t>(i)] =
        out.final_fit.identifiable[static_cast<std::size_t>(i)];
    out.stderr_p[i] = out.final_fit.stderr_x[i];
  }
  // Agreement of the product monomials with the recovered parameters.
  const double pmax2 = std::max(1e-300, p.cwiseAbs2().maxCoeff());
  for (std::size_t c = 0; c < out.joint.monomials.size(); ++c) {
    int i = 0, j = 0;
    monomial_params(out.joint.monomials[c], i, j);
    if (j < 0 || !out.joint.fit.identifiable[c]) continue;
    out.product_consistency =
        std::max(out.product_consistency,
                 std::abs(out.joint.fit.x[static_cast<Eigen::Index>(c)] - p[i] * p[j]) / pmax2);
  }
  return out;
}

}  // namespace abbe::identify
