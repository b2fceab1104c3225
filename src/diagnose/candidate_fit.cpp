#include "candidate_fit.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <utility>

#include "abbe/diagnose/selection.hpp"

namespace abbe::diagnose::selection {

double delta_rss(const Mat& C, const Mat& CtC, const Mat& QtC, const Vec& r, Vec* beta) {
  const Vec b = C.transpose() * r;
  Mat G = CtC;
  if (QtC.rows() > 0) G.noalias() -= QtC.transpose() * QtC;
  for (Eigen::Index c = 0; c < G.rows(); ++c)
    if (!(G(c, c) > 1e-8 * CtC(c, c)) || CtC(c, c) <= 0.0) return -1.0;
  Eigen::LDLT<Mat> ldlt(G);
  const Vec x = ldlt.solve(b);
  if (beta) *beta = x;
  return b.dot(x);
}

Cached cached(const Problem& pb, const Term& t, const Mat& Q, std::vector<double> aliases) {
  Cached c{t, term_columns(pb, t), Mat(), Mat(), std::move(aliases)};
  c.CtC = c.C.transpose() * c.C;
  c.QtC = Q.transpose() * c.C;
  return c;
}

double removes(const Problem& pb, const Term& t, const Mat& Q, const Vec& r) {
  const Mat C = term_columns(pb, t);
  return delta_rss(C, C.transpose() * C, Q.transpose() * C, r);
}

void point_sums(const Problem& pb, const Vec& r, Mat& R, Mat& W) {
  const auto np = static_cast<Eigen::Index>(pb.points.size());
  R = Mat::Zero(np, 3);
  W = Mat::Zero(np, 3);
  for (std::size_t o = 0; o < pb.obs.size(); ++o) {
    const Observation& ob = pb.obs[o];
    const auto p = static_cast<Eigen::Index>(ob.point);
    R.row(p) += r[static_cast<Eigen::Index>(o)] * ob.u.transpose();
    W.row(p) += ob.u.cwiseAbs2().transpose();
  }
}

Mat generic_basis(const Problem& pb, const Term& t) {
  Term one = t;
  one.direction = 0;
  const int k = t.columns();
  Mat B(static_cast<Eigen::Index>(pb.points.size()), k);
  Eigen::Matrix<double, 3, Eigen::Dynamic> g(3, k);
  for (std::size_t p = 0; p < pb.points.size(); ++p) {
    one.basis(pb.points[p], g);
    B.row(static_cast<Eigen::Index>(p)) = g.row(0);
  }
  return B;
}

double motion_squared(const Problem& pb, const Term& t) {
  const int k = t.columns();
  Eigen::Matrix<double, 3, Eigen::Dynamic> g(3, k);
  double s = 0.0;
  for (const Observation& ob : pb.obs) {
    t.basis(pb.points[ob.point], g);
    s += g.squaredNorm();
  }
  return s;
}

double abs_correlation(const Vec& a, const Vec& b) {
  return std::abs(a.dot(b)) / std::max(a.norm() * b.norm(), 1e-300);
}

double removed_by(const Mat& C, const Mat& Q, const Vec& r) {
  const Vec b = C.transpose() * r;
  Mat G = C.transpose() * C;
  if (Q.cols() > 0) {
    const Mat QtC = Q.transpose() * C;
    G.noalias() -= QtC.transpose() * QtC;
  }
  G.diagonal().array() += 1e-12 * std::max(G.trace(), 1e-300) / static_cast<double>(G.rows());
  return b.dot(G.ldlt().solve(b));
}

}  // namespace abbe::diagnose::selection
