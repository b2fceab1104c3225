// Second-order dual numbers: arithmetic against the Taylor expansion of
// functions of (x + h), and use as an Eigen scalar.
#include "abbe/model/dual2.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>

namespace abbe::model {
namespace {

// Evaluates f on a + ε-part and compares with the Taylor coefficients of
// g(t) = f(a0 + a1 t + a2 t²) from finite differences.
template <typename F>
void expect_taylor(F f, Dual2 a, double tol) {
  auto g = [&](double t) { return f(a.v + a.e1 * t + a.e2 * t * t); };
  const double h = 1e-3;
  double d1 = (g(h) - g(-h)) / (2 * h);
  double d2 = (g(h) - 2 * g(0) + g(-h)) / (h * h);
  Dual2 r = f(a);
  EXPECT_NEAR(r.v, g(0), 1e-14);
  EXPECT_NEAR(r.e1, d1, tol);
  EXPECT_NEAR(r.e2, 0.5 * d2, tol);
}

TEST(Dual2, ProductTruncatesAtEpsilonCubed) {
  Dual2 a(2.0, 3.0, 5.0), b(7.0, 11.0, 13.0);
  Dual2 c = a * b;
  EXPECT_EQ(c.v, 14.0);
  EXPECT_EQ(c.e1, 2.0 * 11.0 + 3.0 * 7.0);
  EXPECT_EQ(c.e2, 2.0 * 13.0 + 3.0 * 11.0 + 5.0 * 7.0);
  Dual2 eps(0.0, 1.0, 0.0);
  Dual2 e3 = eps * eps * eps;
  EXPECT_EQ(e3.v, 0.0);
  EXPECT_EQ(e3.e1, 0.0);
  EXPECT_EQ(e3.e2, 0.0);
  EXPECT_EQ((eps * eps).e2, 1.0);
}

TEST(Dual2, DivisionInvertsProduct) {
  Dual2 a(2.0, 3.0, 5.0), b(7.0, -11.0, 13.0);
  Dual2 q = (a * b) / b;
  EXPECT_NEAR(q.v, a.v, 1e-14);
  EXPECT_NEAR(q.e1, a.e1, 1e-13);
  EXPECT_NEAR(q.e2, a.e2, 1e-13);
  expect_taylor([](auto x) { return 1.0 / x; }, Dual2(1.5, 0.7, -0.2), 1e-6);
}

TEST(Dual2, FunctionsFollowTheTaylorSeries) {
  Dual2 a(0.8, 0.3, -0.4);
  expect_taylor(
      [](auto x) {
        using std::sqrt;
        return sqrt(x);
      },
      a, 1e-6);
  expect_taylor(
      [](auto x) {
        using std::sin;
        return sin(x);
      },
      a, 1e-6);
  expect_taylor(
      [](auto x) {
        using std::cos;
        return cos(x);
      },
      a, 1e-6);
  expect_taylor([](auto x) { return x * x * x - 2.0 * x + 1.0; }, a, 1e-6);
}

TEST(Dual2, MixesWithDouble) {
  Dual2 a(1.0, 2.0, 3.0);
  Dual2 b = 2.0 * a + 1.0 - a / 2.0;
  EXPECT_EQ(b.v, 2.5);
  EXPECT_EQ(b.e1, 3.0);
  EXPECT_EQ(b.e2, 4.5);
  Dual2 c = 1.0 - a;
  EXPECT_EQ(c.e1, -2.0);
}

TEST(Dual2, WorksAsAnEigenScalar) {
  using M3 = Eigen::Matrix<Dual2, 3, 3>;
  using V3 = Eigen::Matrix<Dual2, 3, 1>;
  M3 m = M3::Identity();
  m(0, 1) = Dual2(0.0, -1.0, 0.0);
  m(1, 0) = Dual2(0.0, 1.0, 0.0);
  Eigen::Vector3d p(1.0, 2.0, 3.0);
  V3 r = m * p;  // Dual2 × double through ScalarBinaryOpTraits
  EXPECT_EQ(r[0].v, 1.0);
  EXPECT_EQ(r[0].e1, -2.0);
  EXPECT_EQ(r[1].e1, 1.0);
  V3 r2 = m * r;
  EXPECT_EQ(r2[0].e2, -1.0);  // (−ε)(ε) on the diagonal path
  V3 s = 2.0 * r + r;
  EXPECT_EQ(s[2].v, 9.0);
  Dual2 dot = r.dot(r);
  EXPECT_EQ(dot.v, 14.0);
  EXPECT_EQ(dot.e1, 2.0 * (1.0 * -2.0 + 2.0 * 1.0));
}

}  // namespace
}  // namespace abbe::model
