// Scales of several axes that agree within their uncertainties: one
// isotropic scale (isotropic_scale.hpp) — hand-computed weighted mean and
// χ², and the cases that are not one.
#include <gtest/gtest.h>

#include <cmath>

#include "abbe/diagnose/isotropic_scale.hpp"

namespace abbe::diagnose {
namespace {

SelectedTerm scale(int axis, double ppm, double u) {
  SelectedTerm st;
  st.term.kind = TermKind::scale;
  st.term.axis = axis;
  st.term.direction = axis;
  st.term.coef = {ppm};
  st.term.stderr_ = {u};
  return st;
}

TEST(DiagnoseIsotropicScale, TwoScalesThatAgreeGiveTheirWeightedMean) {
  // −33.9 ± 0.68 and −35.3 ± 0.85 ppm (plate 1597A redrilled): weights
  // 1/0.4624 and 1/0.7225; mean −34.446, u = 0.531, χ² = 1.65 (χ²₁ 5 %: 3.84).
  const IsotropicScale r = isotropic_scale({scale(1, -35.3, 0.85), scale(0, -33.9, 0.68)});
  ASSERT_TRUE(r.found);
  EXPECT_EQ(r.axes, (std::vector<int>{0, 1}));  // in axis order
  const double w0 = 1.0 / (0.68 * 0.68), w1 = 1.0 / (0.85 * 0.85);
  const double mean = (w0 * -33.9 + w1 * -35.3) / (w0 + w1);
  EXPECT_NEAR(r.ppm, mean, 1e-12);
  EXPECT_NEAR(r.u_ppm, 1.0 / std::sqrt(w0 + w1), 1e-12);
  EXPECT_NEAR(r.chi2, w0 * std::pow(-33.9 - mean, 2) + w1 * std::pow(-35.3 - mean, 2), 1e-12);
  EXPECT_NEAR(r.kelvin_aluminium(), mean / 23.0, 1e-12);
  EXPECT_NEAR(r.kelvin_steel(), mean / 11.5, 1e-12);
}

TEST(DiagnoseIsotropicScale, ScalesThatDifferAreNotOne) {
  // 10 ± 1 and 20 ± 1 ppm: χ² = 50.
  EXPECT_FALSE(isotropic_scale({scale(0, 10.0, 1.0), scale(1, 20.0, 1.0)}).found);
  // Three that agree; then one of them off.
  EXPECT_TRUE(
      isotropic_scale({scale(0, 10.0, 1.0), scale(1, 11.0, 1.0), scale(2, 9.5, 1.0)}).found);
  EXPECT_FALSE(
      isotropic_scale({scale(0, 10.0, 1.0), scale(1, 11.0, 1.0), scale(2, 19.5, 1.0)}).found);
}

TEST(DiagnoseIsotropicScale, OnlyNamedScalesOfTwoAxesCount) {
  // Zero in, nothing out; one scale alone is no isotropy.
  EXPECT_FALSE(isotropic_scale({}).found);
  EXPECT_FALSE(isotropic_scale({scale(0, 10.0, 1.0)}).found);
  // An ambiguous or not significant scale is not a name.
  SelectedTerm amb = scale(1, 10.0, 1.0);
  amb.ambiguous_with = {"cyclic Y→Y (20 mm)"};
  EXPECT_FALSE(isotropic_scale({scale(0, 10.0, 1.0), amb}).found);
  SelectedTerm weak = scale(1, 10.0, 1.0);
  weak.significant = false;
  EXPECT_FALSE(isotropic_scale({scale(0, 10.0, 1.0), weak}).found);
  // Another kind is not a scale.
  SelectedTerm sq = scale(1, 10.0, 1.0);
  sq.term.kind = TermKind::squareness;
  EXPECT_FALSE(isotropic_scale({scale(0, 10.0, 1.0), sq}).found);
}

// A smooth function whose linear part holds a scale (plate 2130A: an
// `unexplained` dX(x, y) and dY(x, y) with scales −23.9 ± 0.89 and
// −26.1 ± 0.77 ppm in them).
SelectedTerm smooth_with_scale(int axis, double ppm, double u) {
  SelectedTerm st;
  st.term.kind = TermKind::unexplained;
  st.term.direction = axis;
  st.term.vars = {0, 1};
  st.linear_parts = {scale(axis, ppm, u).term};
  st.linear_share = 0.5;
  return st;
}

TEST(DiagnoseIsotropicScale, ASmoothFunctionsLinearPartStandsInForAMissingNamedScale) {
  const IsotropicScale r =
      isotropic_scale({smooth_with_scale(0, -23.9, 0.89), smooth_with_scale(1, -26.1, 0.77)});
  ASSERT_TRUE(r.found);
  EXPECT_EQ(r.axes, (std::vector<int>{0, 1}));
  EXPECT_EQ(r.from_linear_part, (std::vector<bool>{true, true}));
  const double w0 = 1.0 / (0.89 * 0.89), w1 = 1.0 / (0.77 * 0.77);
  EXPECT_NEAR(r.ppm, (w0 * -23.9 + w1 * -26.1) / (w0 + w1), 1e-12);
  // A named scale of the axis comes first: its value, not the part's.
  const IsotropicScale named = isotropic_scale(
      {smooth_with_scale(0, -30.0, 0.5), scale(0, -25.0, 1.0), smooth_with_scale(1, -26.0, 1.0)});
  ASSERT_TRUE(named.found);
  EXPECT_EQ(named.from_linear_part, (std::vector<bool>{false, true}));
  EXPECT_NEAR(named.ppm, -25.5, 1e-12);
  // A part whose uncertainty is not below its value does not count, nor
  // one that holds less than 1 % of its function (not shown either).
  EXPECT_FALSE(isotropic_scale({scale(0, -25.0, 1.0), smooth_with_scale(1, -0.9, 1.0)}).found);
  SelectedTerm faint = smooth_with_scale(1, -26.0, 1.0);
  faint.linear_share = 0.005;
  EXPECT_FALSE(isotropic_scale({scale(0, -25.0, 1.0), faint}).found);
}

}  // namespace
}  // namespace abbe::diagnose
