#include "span.hpp"

namespace abbe::diagnose::span {

void append_orthonormal(Eigen::MatrixXd& Q, const Eigen::MatrixXd& C, double rel_tol) {
  for (Eigen::Index c = 0; c < C.cols(); ++c) {
    Eigen::VectorXd q = C.col(c);
    const double n0 = q.norm();
    if (n0 == 0.0) continue;
    for (int pass = 0; pass < 2; ++pass)
      if (Q.cols() > 0) q -= Q * (Q.transpose() * q);
    const double n = q.norm();
    if (!(n > rel_tol * n0)) continue;
    Q.conservativeResize(Eigen::NoChange, Q.cols() + 1);
    Q.col(Q.cols() - 1) = q / n;
  }
}

Eigen::MatrixXd orthonormal(const Eigen::MatrixXd& A) {
  Eigen::MatrixXd Q(A.rows(), 0);
  append_orthonormal(Q, A, 1e-9);
  return Q;
}

Eigen::MatrixXd residual_of(const Eigen::MatrixXd& Q, const Eigen::MatrixXd& C) {
  return Q.cols() > 0 ? Eigen::MatrixXd(C - Q * (Q.transpose() * C)) : C;
}

Eigen::MatrixXd columns_of(const Problem& pb, const std::vector<Term>& terms) {
  Eigen::Index k = 0;
  for (const Term& t : terms) k += t.columns();
  Eigen::MatrixXd D(static_cast<Eigen::Index>(pb.obs.size()), k);
  Eigen::Index c = 0;
  for (const Term& t : terms) {
    D.middleCols(c, t.columns()) = term_columns(pb, t);
    c += t.columns();
  }
  return D;
}

Eigen::MatrixXd datum_columns(const Problem& pb, const std::vector<SelectedTerm>& datum) {
  std::vector<Term> terms;
  terms.reserve(datum.size());
  for (const SelectedTerm& d : datum) terms.push_back(d.term);
  return columns_of(pb, terms);
}

Eigen::MatrixXd basis_of(const Eigen::MatrixXd& D, const std::vector<Eigen::MatrixXd>& blocks,
                         const std::vector<bool>& use) {
  Eigen::Index k = D.cols();
  for (std::size_t f = 0; f < blocks.size(); ++f)
    if (use[f]) k += blocks[f].cols();
  Eigen::MatrixXd A(D.rows(), k);
  A.leftCols(D.cols()) = D;
  Eigen::Index c = D.cols();
  for (std::size_t f = 0; f < blocks.size(); ++f)
    if (use[f]) {
      A.middleCols(c, blocks[f].cols()) = blocks[f];
      c += blocks[f].cols();
    }
  return orthonormal(A);
}

double SwapBasis::removes(const Eigen::MatrixXd& C) const {
  const Eigen::MatrixXd Qc = orthonormal(residual_of(QA, C));
  return Qc.cols() > 0 ? (Qc.transpose() * rA).squaredNorm() : 0.0;
}

SwapBasis swap_basis(const Problem& pb, const Eigen::MatrixXd& D,
                     const std::vector<Eigen::MatrixXd>& cols, const std::vector<bool>& use,
                     std::size_t e) {
  SwapBasis b;
  b.QA = basis_of(D, cols, use);
  b.rA = residual_of(b.QA, pb.y);
  b.Ce = residual_of(b.QA, cols[e]);
  const Eigen::MatrixXd Qe = orthonormal(b.Ce);
  b.rank = Qe.cols();
  b.d_e = b.rank > 0 ? (Qe.transpose() * b.rA).squaredNorm() : 0.0;
  return b;
}

}  // namespace abbe::diagnose::span
