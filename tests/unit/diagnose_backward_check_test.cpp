// The backward check of the selection (src/diagnose/backward_check.hpp):
// each named effect tested again beside the datum and the other named
// effects. Hand-computed cases on orthogonal columns, zero in, invariance
// under the scale of a column, and smooth functions left out of the test.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "abbe/diagnose/statistics.hpp"
#include "src/diagnose/backward_check.hpp"

namespace abbe::diagnose::selection {
namespace {

Term named(TermKind kind, int axis) {
  Term t;
  t.kind = kind;
  t.axis = axis;
  t.direction = axis;
  return t;
}

// A datum constant and three one-column named effects on 40 observations:
// columns that are orthogonal to each other and to the constant (Legendre
// polynomials of degree 1–3 on a symmetric grid are, up to rounding, not
// exactly; so Gram–Schmidt them here).
struct Fixture {
  Mat X{40, 4};
  Mat Qd;
  std::vector<Term> chosen;
  Fixture() {
    for (Eigen::Index i = 0; i < X.rows(); ++i) {
      const double u = -1.0 + 2.0 * static_cast<double>(i) / static_cast<double>(X.rows() - 1);
      X.row(i) << 1.0, u, u * u, u * u * u;
    }
    const Eigen::HouseholderQR<Mat> qr(X);
    X = qr.householderQ() * Mat::Identity(X.rows(), X.cols());  // orthonormal, same span order
    Qd = X.leftCols(1);
    Term datum;
    datum.kind = TermKind::setup_offset;
    chosen = {datum, named(TermKind::scale, 0), named(TermKind::reversal, 1),
              named(TermKind::squareness, 2)};
  }
};

TEST(DiagnoseBackwardCheck, ZeroInEveryEffectIsRedundant) {
  const Fixture f;
  const Vec y = Vec::Zero(f.X.rows());
  const auto weak = least_needed_named(f.X, f.Qd, y, f.chosen, 1, 0.25, 0.01);
  ASSERT_TRUE(weak.has_value());
  EXPECT_NEAR(weak->delta_rss, 0.0, 1e-12);
}

TEST(DiagnoseBackwardCheck, HandComputedOnOrthonormalColumns) {
  const Fixture f;
  // y = 3·c1 + 2·c2 + 0.1·c3 + 7 (the datum): on orthonormal columns the
  // RSS rises by coef² when an effect is dropped.
  const Vec y = 7.0 * f.X.col(0) + 3.0 * f.X.col(1) + 2.0 * f.X.col(2) + 0.1 * f.X.col(3);
  const double s2 = 0.25, alpha = 0.01;
  const auto weak = least_needed_named(f.X, f.Qd, y, f.chosen, 1, s2, alpha);
  ASSERT_TRUE(weak.has_value());
  EXPECT_EQ(weak->index, 3u);
  EXPECT_NEAR(weak->delta_rss, 0.01, 1e-9);
  EXPECT_NEAR(weak->threshold, s2 * chi2_upper_quantile(1, alpha), 1e-12);
  // Every effect clearly needed: nothing is returned.
  const Vec strong = y + 1.9 * f.X.col(3);  // c3's coefficient 2: ΔRSS 4 > 0.25·6.63
  EXPECT_FALSE(least_needed_named(f.X, f.Qd, strong, f.chosen, 1, s2, alpha).has_value());
}

TEST(DiagnoseBackwardCheck, TheScaleOfAColumnChangesNothing) {
  Fixture f;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 0.5);
  Vec y = 2.0 * f.X.col(1) + 0.2 * f.X.col(2) + 1.5 * f.X.col(3);
  for (Eigen::Index i = 0; i < y.size(); ++i) y[i] += noise(rng);
  // Correlated named columns: the second takes part of the first.
  f.X.col(2) += 0.6 * f.X.col(1);
  const auto a = least_needed_named(f.X, f.Qd, y, f.chosen, 1, 0.25, 0.01);
  Mat scaled = f.X;
  scaled.col(2) *= 1e4;
  scaled.col(1) *= 1e-3;
  const auto b = least_needed_named(scaled, f.Qd, y, f.chosen, 1, 0.25, 0.01);
  ASSERT_EQ(a.has_value(), b.has_value());
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->index, b->index);
  EXPECT_NEAR(a->delta_rss, b->delta_rss, 1e-8 * std::max(1.0, a->delta_rss));
}

TEST(DiagnoseBackwardCheck, SmoothFunctionsAreNotTested) {
  Fixture f;
  // The third term a smooth function that holds the second's column: the
  // named effect is still needed beside the other named ones, and the
  // smooth function is never the one returned.
  f.chosen[3].kind = TermKind::unexplained;
  f.chosen[3].vars = {0};
  f.chosen[3].degree = 1;
  f.X.col(3) = f.X.col(2);
  const Vec y = 3.0 * f.X.col(1) + 4.0 * f.X.col(2);
  const auto weak = least_needed_named(f.X, f.Qd, y, f.chosen, 1, 0.25, 0.01);
  EXPECT_FALSE(weak.has_value());
}

}  // namespace
}  // namespace abbe::diagnose::selection
