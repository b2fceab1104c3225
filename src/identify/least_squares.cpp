#include "abbe/identify/least_squares.hpp"

#include <fmt/format.h>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>

namespace abbe::identify {

LeastSquaresResult solve_least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                                       const LeastSquaresOptions& options) {
  const Eigen::Index m = a.rows(), n = a.cols();
  LeastSquaresResult out;
  out.rows = static_cast<long>(m);
  // Column scaling: unit-norm columns; an all-zero column keeps scale 1.
  Eigen::VectorXd scale = a.colwise().norm().transpose();
  for (Eigen::Index j = 0; j < n; ++j)
    if (!(scale[j] > 0.0)) scale[j] = 1.0;
  const Eigen::MatrixXd as = a * scale.cwiseInverse().asDiagonal();

  // A_s = Q R, R = U Σ Vᵀ → the SVD of A_s on the n × n triangle.
  Eigen::MatrixXd r;
  Eigen::VectorXd qtb;
  if (m > n) {
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(as);
    r = qr.matrixQR().topRows(n).triangularView<Eigen::Upper>();
    qtb = (qr.householderQ().adjoint() * b).head(n);
  } else {
    r = as;
    qtb = b;
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd& sv = svd.singularValues();
  out.singular_values = sv;
  const double smax = sv.size() > 0 ? sv[0] : 0.0;
  int rank = 0;
  for (Eigen::Index i = 0; i < sv.size(); ++i)
    if (sv[i] > options.rank_tolerance * smax) ++rank;
  out.rank = rank;
  if (rank == n && n > 0 && sv[n - 1] > 0.0) out.condition = smax / sv[n - 1];
  if (rank > 0) out.condition_in_rank = smax / sv[rank - 1];

  const Eigen::MatrixXd& u = svd.matrixU();
  const Eigen::MatrixXd& v = svd.matrixV();
  Eigen::VectorXd xs = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < rank; ++i) xs += v.col(i) * (u.col(i).dot(qtb) / sv[i]);
  out.x = xs.cwiseQuotient(scale);

  const Eigen::VectorXd res = b - a * out.x;
  const double ss = res.squaredNorm();
  out.residual_rms = m > 0 ? std::sqrt(ss / static_cast<double>(m)) : 0.0;
  const long dof = static_cast<long>(m) - rank;
  out.sigma = dof > 0 ? std::sqrt(ss / static_cast<double>(dof)) : 0.0;

  // Null space (scaled coordinates) and identifiability of each unknown.
  Eigen::MatrixXd vn = v.rightCols(n - rank);
  out.identifiable.assign(static_cast<std::size_t>(n), true);
  for (Eigen::Index j = 0; j < n; ++j)
    if (vn.cols() > 0 && vn.row(j).norm() > 1e-6)
      out.identifiable[static_cast<std::size_t>(j)] = false;
  for (Eigen::Index c = 0; c < vn.cols(); ++c) {
    Eigen::VectorXd d = vn.col(c).cwiseQuotient(scale);
    d /= d.norm();
    out.null_space.push_back({d, vn.col(c)});
  }
  // The rank is decided on the scaled problem, but of all least-squares
  // solutions return the one of minimum norm in the caller's unknowns (the
  // Moore–Penrose solution proper): project the null space, taken in those
  // unknowns, out of x. Identifiable unknowns are untouched by this.
  if (vn.cols() > 0) {
    const Eigen::MatrixXd nd = scale.cwiseInverse().asDiagonal() * vn;
    Eigen::HouseholderQR<Eigen::MatrixXd> nq(nd);
    const Eigen::MatrixXd q = nq.householderQ() * Eigen::MatrixXd::Identity(n, vn.cols());
    out.x -= q * (q.transpose() * out.x);
  }
  // cov(x_s) = σ² V_r Σ_r⁻² V_rᵀ, then back to the original scale.
  out.stderr_x = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::quiet_NaN());
  for (Eigen::Index j = 0; j < n; ++j) {
    if (!out.identifiable[static_cast<std::size_t>(j)]) continue;
    double var = 0.0;
    for (int i = 0; i < rank; ++i) var += std::pow(v(j, i) / sv[i], 2);
    out.stderr_x[j] = out.sigma * std::sqrt(var) / scale[j];
  }
  return out;
}

std::string describe_combination(const Eigen::VectorXd& direction,
                                 const std::vector<std::string>& names, double floor) {
  std::string s;
  Eigen::Index lead = 0;
  direction.cwiseAbs().maxCoeff(&lead);
  const double sign = direction[lead] < 0.0 ? -1.0 : 1.0;
  for (Eigen::Index j = 0; j < direction.size(); ++j) {
    const double c = sign * direction[j];
    if (std::abs(c) < floor) continue;
    const std::string& name = names[static_cast<std::size_t>(j)];
    if (s.empty())
      s = fmt::format("{:.3g}·{}", c, name);
    else
      s += fmt::format(" {} {:.3g}·{}", c < 0 ? "−" : "+", std::abs(c), name);
  }
  return s;
}

}  // namespace abbe::identify
