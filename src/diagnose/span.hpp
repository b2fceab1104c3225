#pragma once
// Column spans of the checks after the fit (design_ambiguity.cpp,
// rival_check.cpp): an orthonormal basis by two-pass Gram–Schmidt and the
// part of columns outside a span.
#include <Eigen/Core>
#include <vector>

#include "abbe/diagnose/residuals.hpp"
#include "abbe/diagnose/selection.hpp"

namespace abbe::diagnose::span {

// Q (orthonormal columns) extended by the part of C's columns outside its
// span, two-pass Gram–Schmidt; a column whose part outside is at most
// `rel_tol` of its norm (or zero) is dropped.
void append_orthonormal(Eigen::MatrixXd& Q, const Eigen::MatrixXd& C, double rel_tol = 1e-10);

// Orthonormal basis of the span of A's columns; a column already in the
// span of the ones before it (or zero) is dropped.
Eigen::MatrixXd orthonormal(const Eigen::MatrixXd& A);

// C minus its projection on the span of the orthonormal columns of Q.
Eigen::MatrixXd residual_of(const Eigen::MatrixXd& Q, const Eigen::MatrixXd& C);

// The terms' columns side by side (observations × their columns).
Eigen::MatrixXd columns_of(const Problem& problem, const std::vector<Term>& terms);
// The same for fitted datum terms.
Eigen::MatrixXd datum_columns(const Problem& problem, const std::vector<SelectedTerm>& datum);

// Orthonormal basis of "everything else of the fit": the columns D and the
// blocks whose `use` is true.
Eigen::MatrixXd basis_of(const Eigen::MatrixXd& D, const std::vector<Eigen::MatrixXd>& blocks,
                         const std::vector<bool>& use);

// A swap test's basis for the effect block e of `cols`: everything else of
// the fit (QA: the datum D and the blocks `use`), the data and the effect's
// columns beside it (rA, Ce), what the effect removes there (d_e, over its
// `rank` independent columns), and what other columns remove in its place.
struct SwapBasis {
  Eigen::MatrixXd QA, Ce;
  Eigen::VectorXd rA;
  double d_e = 0.0;
  Eigen::Index rank = 0;
  double removes(const Eigen::MatrixXd& C) const;
};
SwapBasis swap_basis(const Problem& problem, const Eigen::MatrixXd& D,
                     const std::vector<Eigen::MatrixXd>& cols, const std::vector<bool>& use,
                     std::size_t e);

}  // namespace abbe::diagnose::span
