#pragma once
// The levels of a design's axis — a grid's levels, a laser line's targets —
// and the functions of them, that the design checks (design_ambiguity.cpp,
// cycle_period_test.cpp) compare the selected effects with.
#include <Eigen/Dense>
#include <cstddef>
#include <vector>

#include "abbe/diagnose/design_ambiguity.hpp"
#include "abbe/diagnose/residuals.hpp"

namespace abbe::diagnose::design {

using Mat = Eigen::MatrixXd;
using Vec = Eigen::VectorXd;

// The level of position s among the levels lv (sorted).
std::size_t level_index(const std::vector<double>& lv, double s);

// The distinct positions among `v` when they are few (3 to max_levels) and
// at least twice the catalogue's shortest period apart; else empty.
std::vector<double> levels_of(std::vector<double> v, const DesignAmbiguityOptions& o,
                              double min_period_mm);

// The functions of the levels of s_j, per direction: the columns
// u_i·[level = l], without forming them (n × 3·levels). Each observation
// lies in one level, so the span is a sum of one 3-column block per level,
// and what it holds of a column is a 3 × 3 solve per level.
class LevelSpan {
 public:
  LevelSpan(const Problem& pb, int j, const std::vector<double>& lv)
      : pb_(pb), level_(pb.obs.size()), gram_(lv.size(), Eigen::Matrix3d::Zero()) {
    for (std::size_t ob = 0; ob < pb.obs.size(); ++ob) {
      level_[ob] = level_index(lv, pb.points[pb.obs[ob].point].s[j]);
      gram_[level_[ob]] += pb.obs[ob].u * pb.obs[ob].u.transpose();
    }
    for (Eigen::Matrix3d& g : gram_)
      g = g.completeOrthogonalDecomposition().pseudoInverse().eval();  // G⁺ per level
  }

  // The squared norm of the columns of C projected on the span.
  double projected(const Mat& C) const {
    double sum = 0.0;
    for (Eigen::Index c = 0; c < C.cols(); ++c) {
      std::vector<Eigen::Vector3d> g(gram_.size(), Eigen::Vector3d::Zero());
      for (std::size_t ob = 0; ob < level_.size(); ++ob)
        g[level_[ob]] += pb_.obs[ob].u * C(static_cast<Eigen::Index>(ob), c);
      for (std::size_t l = 0; l < g.size(); ++l) sum += g[l].dot(gram_[l] * g[l]);
    }
    return sum;
  }

  // What the functions of the levels in direction i (u_i·[level = l]) remove
  // of r_A when added to the orthonormal span QA (r_A ⟂ QA): bᵀ M⁺ b with
  // b = Cᵀ r_A and M = CᵀC − (QAᵀC)ᵀ(QAᵀC), each a sum over observations.
  double removes_in_place(const Mat& QA, const Vec& rA, int i) const {
    const InPlace ip = in_place(QA, rA, i);
    return ip.b.dot(ip.M.completeOrthogonalDecomposition().solve(ip.b));
  }

  // The same sums for functions of the levels given by their values V
  // (levels × k): what they remove in place, (Vᵀb)ᵀ(VᵀMV)⁺(Vᵀb), for many V
  // at the cost of one pass over the observations.
  struct InPlace {
    Vec b;
    Mat M;
    double removes(const Mat& V) const {
      const Vec bv = V.transpose() * b;
      const Mat Mv = V.transpose() * M * V;
      return bv.dot(Mv.completeOrthogonalDecomposition().solve(bv));
    }
  };
  InPlace in_place(const Mat& QA, const Vec& rA, int i) const {
    const auto m = static_cast<Eigen::Index>(gram_.size());
    InPlace ip{Vec::Zero(m), Mat()};
    Vec diag = Vec::Zero(m);
    Mat P = Mat::Zero(QA.cols(), m);
    for (std::size_t ob = 0; ob < level_.size(); ++ob) {
      const double c = pb_.obs[ob].u[i];
      if (c == 0.0) continue;
      const auto l = static_cast<Eigen::Index>(level_[ob]);
      const auto row = static_cast<Eigen::Index>(ob);
      ip.b[l] += c * rA[row];
      diag[l] += c * c;
      if (QA.cols() > 0) P.col(l) += c * QA.row(row).transpose();
    }
    ip.M = Mat(diag.asDiagonal()) - P.transpose() * P;
    return ip;
  }

 private:
  const Problem& pb_;
  std::vector<std::size_t> level_;     // per observation
  std::vector<Eigen::Matrix3d> gram_;  // per level: (Σ u uᵀ)⁺
};

}  // namespace abbe::diagnose::design
