#pragma once
// Least squares of the selection's candidates against the span it has
// selected so far (selection.cpp and its parts): a candidate's columns with
// their Gram matrices cached, what it removes from the residual, and the
// point-level sums the smooth families and the parameter scans use.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "abbe/diagnose/residuals.hpp"
#include "abbe/diagnose/term.hpp"

namespace abbe::diagnose::selection {

using Mat = Eigen::MatrixXd;
using Vec = Eigen::VectorXd;

struct Cached {
  Term term;
  Mat C;                        // observations × k
  Mat CtC;                      // k × k
  Mat QtC;                      // p × k, extended as Q grows
  std::vector<double> aliases;  // cyclic: other periods that fit these points as well
};

// What a step found a pick could be instead: other names (rivals) and, for
// a cycle, other periods that fit these points as well (its aliases: the
// same effect, its period not resolved).
struct Alternatives {
  std::vector<std::string> names;
  std::vector<double> periods_mm;
  bool empty() const { return names.empty() && periods_mm.empty(); }
  void clear() {
    names.clear();
    periods_mm.clear();
  }
};

// ΔRSS of adding C to the selected span Q (r ⟂ Q; QtC = QᵀC). Returns −1
// when C lies in span(Q) (nothing new to fit); beta: the coefficients.
double delta_rss(const Mat& C, const Mat& CtC, const Mat& QtC, const Vec& r, Vec* beta = nullptr);

// Term t with its columns and their products beside span(Q).
Cached cached(const Problem& pb, const Term& t, const Mat& Q, std::vector<double> aliases = {});
// What term t removes of r beside span(Q) (r ⟂ Q): delta_rss of its columns.
double removes(const Problem& pb, const Term& t, const Mat& Q, const Vec& r);

// Point-level sums of the residual: R(p,·) = Σ_o u_o r_o; W(p,i) = Σ_o u_o,i².
void point_sums(const Problem& pb, const Vec& r, Mat& R, Mat& W);

// Point-level basis of an unexplained term (points × k, the direction ignored).
Mat generic_basis(const Problem& pb, const Term& t);

// Σ over the observations of |g_c(point)|² (the deviation the term's
// columns make, whatever direction is measured).
double motion_squared(const Problem& pb, const Term& t);

// |cos| of the angle between two fitted contributions.
double abs_correlation(const Vec& a, const Vec& b);

// What the columns C remove of r beside the orthonormal span Q (r ⟂ Q), with
// a tiny ridge for near-dependent columns (a smooth family's): bᵀG⁻¹b.
double removed_by(const Mat& C, const Mat& Q, const Vec& r);

}  // namespace abbe::diagnose::selection
