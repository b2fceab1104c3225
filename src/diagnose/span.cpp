#include "span.hpp"

namespace abbe::diagnose::span {

Eigen::MatrixXd orthonormal(const Eigen::MatrixXd& A) {
  Eigen::MatrixXd Q(A.rows(), 0);
  for (Eigen::Index c = 0; c < A.cols(); ++c) {
    Eigen::VectorXd q = A.col(c);
    const double n0 = q.norm();
    if (n0 == 0.0) continue;
    for (int pass = 0; pass < 2; ++pass)
      if (Q.cols() > 0) q -= Q * (Q.transpose() * q);
    const double n = q.norm();
    if (!(n > 1e-9 * n0)) continue;
    Q.conservativeResize(Eigen::NoChange, Q.cols() + 1);
    Q.col(Q.cols() - 1) = q / n;
  }
  return Q;
}

Eigen::MatrixXd residual_of(const Eigen::MatrixXd& Q, const Eigen::MatrixXd& C) {
  return Q.cols() > 0 ? Eigen::MatrixXd(C - Q * (Q.transpose() * C)) : C;
}

}  // namespace abbe::diagnose::span
