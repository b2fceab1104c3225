#pragma once
// The linear part of a smooth (`unexplained`) function: the scales and
// squarenesses (d_i ∝ s_a for each position variable a of the function, i
// its direction) that the structure it fitted contains — its least-squares
// projection on their columns beside the datum, with standard
// uncertainties. Not a name: a smooth function is chosen where no
// combination of catalogue effects explains the structure, and the linear
// part says how much of it is a scale or a squareness (e.g. a plate's
// isotropic scale inside a distortion the catalogue does not hold).
#include <vector>

#include "abbe/diagnose/selection.hpp"
#include "candidate_fit.hpp"

namespace abbe::diagnose::selection {

// How the smooth function's coefficients came from the data, in the final
// fit's two stages (final_fit.hpp): the named stage (the datum and the named
// effects: its columns and (XᵀX)⁻¹) left r₁ = (I − P_named)·y, and the
// smooth stage fitted its columns to r₁, β = (XᵀX)⁻¹ Xᵀ r₁.
struct SmoothFitMap {
  const Mat& named_X;
  const Mat& named_inv;
  const Mat& smooth_X;
  const Mat& smooth_inv;
  double s2 = 0.0;  // the noise variance per observation
};

// The function st.term (kind unexplained) is the columns [col, col + k) of
// the smooth stage with coefficients beta; Qd: the datum's orthonormal span.
// Fills st.linear_parts (each a Term with coef and stderr_: the standard
// uncertainty of the part as the two stages make it from the data, with
// noise variance s2 per observation) and st.linear_share (the share of the
// function's sum of squares beyond the datum they hold).
void fill_linear_part(const Problem& pb, const SmoothFitMap& fit, Eigen::Index col, const Vec& beta,
                      const Mat& Qd, SelectedTerm& st);

}  // namespace abbe::diagnose::selection
