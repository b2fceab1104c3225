// The linear part of a smooth function (linear_part.hpp): the scale and
// squareness its fitted structure holds, with standard uncertainties. A
// degree-1 function of y is a scale of Y, value and uncertainty; zero in,
// zero out; a structure with no linear part has none; the parts of a
// structure come back within their uncertainties, which match their spread
// over noise draws; the machine's zero and the datum's offset change
// nothing.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <random>

#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/selection.hpp"
#include "diagnose_test_problem.hpp"
#include "src/diagnose/linear_part.hpp"
#include "src/diagnose/span.hpp"

namespace abbe::diagnose {
namespace {

using Mat = Eigen::MatrixXd;
using Vec = Eigen::VectorXd;

// A plate of 121 holes, centred on (cx, cy) at z = 0, read in dx and dy;
// dY = f(u, v) + offset + noise, dX = noise (u, v ∈ [−1, 1] across the
// plate, 600 mm). The holes 11 × 11, 60 mm apart, or (scattered) at the
// same random places for every noise seed.
template <class F>
Problem plate(F f, double offset, double sigma, std::uint64_t seed, double cx = 0.0,
              double cy = 0.0, bool scattered = false) {
  Problem pb;
  std::vector<double> y;
  std::mt19937_64 rng(seed), places(5);
  std::normal_distribution<double> noise(0.0, sigma);
  std::uniform_real_distribution<double> anywhere(-1.0, 1.0);
  for (int i = 0; i < 11; ++i)
    for (int k = 0; k < 11; ++k) {
      double u = (i - 5) / 5.0, v = (k - 5) / 5.0;
      if (scattered) {
        u = anywhere(places);
        v = anywhere(places);
      }
      PointContext pc;
      pc.p = pc.s = Eigen::Vector3d(cx + 300.0 * u, cy + 300.0 * v, 0.0);
      pc.set = "plate";
      const auto point = static_cast<std::uint32_t>(pb.points.size());
      pb.obs.push_back({point, Eigen::Vector3d::UnitX()});
      y.push_back(noise(rng));
      pb.obs.push_back({point, Eigen::Vector3d::UnitY()});
      y.push_back(f(u, v) + offset + noise(rng));
      pb.points.push_back(pc);
      pb.lines.push_back(pb.points.size() + 1);
    }
  test::finish_problem(pb, y, "plate", {true, true, false}, Eigen::Vector3d(cx - 300, cy - 300, 0),
                       Eigen::Vector3d(cx + 300, cy + 300, 0));
  return pb;
}

// dY as a smooth function of `vars` of `degree` over the problem's box.
Term smooth_dy(const Problem& pb, std::vector<int> vars, int degree) {
  Term t;
  t.kind = TermKind::unexplained;
  t.direction = 1;
  t.vars = std::move(vars);
  t.degree = degree;
  for (std::size_t k = 0; k < 4; ++k) {
    t.lo[k] = pb.var_lo[k];
    t.hi[k] = pb.var_hi[k] > pb.var_lo[k] ? pb.var_hi[k] : pb.var_lo[k] + 1.0;
  }
  return t;
}

// The final fit's two stages for a datum and one smooth function (as
// final_fit.cpp): the datum, then the function on what it leaves; then the
// function's linear part.
struct Fitted {
  SelectedTerm st;
  double s2 = 0.0;
  Mat Qd;
};
// `named`: effects fitted with the datum in the first stage.
Fitted fit(const Problem& pb, const Term& smooth, bool rotation = true,
           const std::vector<Term>& named = {}) {
  Fitted r;
  std::vector<Term> datum = build_candidates(pb, CandidateOptions{}).datum;
  if (!rotation)
    datum.erase(std::remove_if(datum.begin(), datum.end(),
                               [](const Term& t) { return t.kind == TermKind::setup_rotation; }),
                datum.end());
  r.Qd = span::orthonormal(span::columns_of(pb, datum));
  datum.insert(datum.end(), named.begin(), named.end());
  const Mat D = span::columns_of(pb, datum);
  const Mat D_inv = (D.transpose() * D).ldlt().solve(Mat::Identity(D.cols(), D.cols()));
  const Vec r1 = pb.y - D * (D_inv * (D.transpose() * pb.y));
  const Mat X = term_columns(pb, smooth);
  const Mat X_inv = (X.transpose() * X).ldlt().solve(Mat::Identity(X.cols(), X.cols()));
  const Vec beta = X_inv * (X.transpose() * r1);
  const double dof = static_cast<double>(pb.y.size() - X.cols() - r.Qd.cols());
  r.s2 = (r1 - X * beta).squaredNorm() / dof;
  r.st.term = smooth;
  selection::fill_linear_part(pb, {D, D_inv, X, X_inv, r.s2}, 0, beta, r.Qd, r.st);
  return r;
}

const Term* part(const SelectedTerm& st, TermKind kind, int axis) {
  for (const Term& t : st.linear_parts)
    if (t.kind == kind && t.axis == axis) return &t;
  return nullptr;
}

TEST(DiagnoseLinearPart, ADegreeOneFunctionOfYIsAScaleOfY) {
  // dY = −25 ppm · s_y (−7.5 µm at the plate's edge) + 4 µm, noise 0.5 µm.
  const Problem pb = plate([](double, double v) { return -25e-3 * 300.0 * v; }, 4.0, 0.5, 1);
  const Fitted f = fit(pb, smooth_dy(pb, {1}, 1));
  ASSERT_EQ(f.st.linear_parts.size(), 1u);
  const Term* sy = part(f.st, TermKind::scale, 1);
  ASSERT_NE(sy, nullptr);
  EXPECT_EQ(sy->direction, 1);
  // The scale fitted beside the datum by hand: c = L̃ᵀy / L̃ᵀL̃, u = √(s²/L̃ᵀL̃).
  Term scale_y;
  scale_y.kind = TermKind::scale;
  scale_y.axis = scale_y.direction = 1;
  Vec L = term_columns(pb, scale_y).col(0);
  L -= f.Qd * (f.Qd.transpose() * L);
  EXPECT_NEAR(sy->coef[0], L.dot(pb.y) / L.squaredNorm(), 1e-9);
  EXPECT_NEAR(sy->stderr_[0], std::sqrt(f.s2 / L.squaredNorm()), 1e-9);
  EXPECT_NEAR(sy->coef[0], -25.0, 3.0 * sy->stderr_[0]);
  EXPECT_NEAR(f.st.linear_share, 1.0, 1e-9);  // the function is its linear part
}

TEST(DiagnoseLinearPart, ZeroInZeroOut) {
  const Problem zero = plate([](double, double) { return 0.0; }, 0.0, 0.0, 1);
  const Fitted f = fit(zero, smooth_dy(zero, {0, 1}, 3));
  ASSERT_EQ(f.st.linear_parts.size(), 2u);  // squareness dY ∝ x, scale Y
  for (const Term& t : f.st.linear_parts) {
    EXPECT_EQ(t.coef[0], 0.0) << t.label();
    EXPECT_EQ(t.stderr_[0], 0.0) << t.label();
  }
  EXPECT_EQ(f.st.linear_share, 0.0);
  // A structure even in u and in v (on this symmetric plate, orthogonal to
  // both linear columns) has no linear part.
  const Problem even =
      plate([](double u, double v) { return 3.0 * (1.5 * u * u - 0.5) * (1.5 * v * v - 0.5); }, 0.0,
            0.0, 1);
  const Fitted g = fit(even, smooth_dy(even, {0, 1}, 3));
  for (const Term& t : g.st.linear_parts) EXPECT_NEAR(t.coef[0], 0.0, 1e-9) << t.label();
  EXPECT_NEAR(g.st.linear_share, 0.0, 1e-12);
  // A term that is not a smooth function has none.
  SelectedTerm named;
  named.term.kind = TermKind::scale;
  named.term.axis = named.term.direction = 1;
  const Mat none, one = Mat::Identity(1, 1), columns = term_columns(even, named.term);
  selection::fill_linear_part(even, {none, none, columns, one, 1.0}, 0, Vec::Ones(1), g.Qd, named);
  EXPECT_TRUE(named.linear_parts.empty());
}

// −25 ppm scale of Y and +12 µrad squareness dY ∝ x inside a structure
// the catalogue does not hold (a saddle of 3 µm), noise 0.8 µm.
double structure(double u, double v) {
  return -25e-3 * 300.0 * v + 12e-3 * 300.0 * u + 3.0 * (1.5 * u * u - 0.5) * (1.5 * v * v - 0.5);
}

TEST(DiagnoseLinearPart, ThePartsComeBackWithinTheirUncertainty) {
  // Over 300 noise draws at the same scattered holes (the function's
  // columns then correlate with the datum's offsets, and the two stages'
  // uncertainty differs from the one-stage formula): each part's mean is
  // its true value, and the spread of its values is the standard
  // uncertainty the fit states. The datum without the plate's rotation,
  // which would take half of a squareness dY ∝ x (and leave the other half
  // in dX, outside the function).
  const int draws = 300;
  double sum[2] = {0, 0}, sum2[2] = {0, 0}, u_sum[2] = {0, 0}, share = 0.0;
  for (int k = 0; k < draws; ++k) {
    const Problem pb =
        plate(structure, 2.0, 0.8, static_cast<std::uint64_t>(100 + k), 0.0, 0.0, true);
    const Fitted f = fit(pb, smooth_dy(pb, {0, 1}, 3), false);
    const Term* p[2] = {part(f.st, TermKind::scale, 1), part(f.st, TermKind::squareness, 0)};
    for (int j = 0; j < 2; ++j) {
      ASSERT_NE(p[j], nullptr);
      sum[j] += p[j]->coef[0];
      sum2[j] += p[j]->coef[0] * p[j]->coef[0];
      u_sum[j] += p[j]->stderr_[0];
    }
    share += f.st.linear_share;
  }
  // The truth: the linear part of the structure without noise (at these
  // scattered holes the saddle has a small linear part of its own).
  const Problem clean = plate(structure, 2.0, 0.0, 1, 0.0, 0.0, true);
  const Fitted c = fit(clean, smooth_dy(clean, {0, 1}, 3), false);
  const double truth[2] = {part(c.st, TermKind::scale, 1)->coef[0],
                           part(c.st, TermKind::squareness, 0)->coef[0]};
  EXPECT_NEAR(truth[0], -25.0, 1.0);
  EXPECT_NEAR(truth[1], 12.0, 1.0);
  for (int j = 0; j < 2; ++j) {
    const double mean = sum[j] / draws;
    const double sd = std::sqrt(std::max(sum2[j] / draws - mean * mean, 0.0));
    const double u = u_sum[j] / draws;
    EXPECT_NEAR(mean, truth[j], 4.0 * u / std::sqrt(draws)) << j;
    EXPECT_NEAR(sd / u, 1.0, 0.15) << j;  // ±15 %: 300 draws give about ±4 % (1σ)
  }
  // The linear part holds most of this structure: 7.5 and 3.6 µm at the
  // edges against a 3 µm saddle.
  EXPECT_GT(share / draws, 0.8);
  EXPECT_LT(share / draws, 1.0);
}

TEST(DiagnoseLinearPart, WhatTheNamedStageTookIsNotInIt) {
  // A scale of Y named beside the function (the final fit's first stage)
  // takes the structure's scale: the function's linear part holds none of
  // it, and next to none of its noise (a spread of a few % of it, where the one-stage
  // formula would state the named scale's uncertainty again).
  Term scale_y;
  scale_y.kind = TermKind::scale;
  scale_y.axis = scale_y.direction = 1;
  const Problem pb = plate(structure, 2.0, 0.8, 3, 0.0, 0.0, true);
  const Fitted alone = fit(pb, smooth_dy(pb, {0, 1}, 3), false);
  const Fitted beside = fit(pb, smooth_dy(pb, {0, 1}, 3), false, {scale_y});
  const Term* a = part(alone.st, TermKind::scale, 1);
  const Term* b = part(beside.st, TermKind::scale, 1);
  ASSERT_TRUE(a && b);
  EXPECT_NEAR(a->coef[0], -25.0, 4.0 * a->stderr_[0]);
  EXPECT_GT(a->stderr_[0], 0.2);
  EXPECT_LT(std::abs(b->coef[0]), 0.5 * a->stderr_[0]);
  EXPECT_LT(b->stderr_[0], 0.1 * a->stderr_[0]);
  // The squareness dY ∝ x, not named, is still the function's.
  EXPECT_NEAR(part(beside.st, TermKind::squareness, 0)->coef[0],
              part(alone.st, TermKind::squareness, 0)->coef[0], 0.5);
}

TEST(DiagnoseLinearPart, APartTheDatumHoldsWholeIsLeftOut) {
  // A datum that holds d_Y ∝ x whole (as a line's rotation would): the
  // squareness is no part beyond it, the scale still is.
  const Problem pb = plate(structure, 0.0, 0.5, 9);
  const Term smooth = smooth_dy(pb, {0, 1}, 3);
  std::vector<Term> datum = build_candidates(pb, CandidateOptions{}).datum;
  Term sq;
  sq.kind = TermKind::squareness;
  sq.axis = 0;
  sq.direction = 1;
  datum.push_back(sq);
  const Mat D = span::columns_of(pb, datum);
  const Mat D_inv = (D.transpose() * D).ldlt().solve(Mat::Identity(D.cols(), D.cols()));
  const Mat Qd = span::orthonormal(D);
  const Mat X = term_columns(pb, smooth);
  const Mat X_inv = (X.transpose() * X).ldlt().solve(Mat::Identity(X.cols(), X.cols()));
  const Vec r1 = pb.y - Qd * (Qd.transpose() * pb.y);
  SelectedTerm st;
  st.term = smooth;
  selection::fill_linear_part(pb, {D, D_inv, X, X_inv, 0.25}, 0, X_inv * (X.transpose() * r1), Qd,
                              st);
  ASSERT_EQ(st.linear_parts.size(), 1u);
  EXPECT_EQ(st.linear_parts[0].kind, TermKind::scale);
  EXPECT_NEAR(st.linear_parts[0].coef[0], -25.0, 4.0 * st.linear_parts[0].stderr_[0]);
  EXPECT_TRUE(std::isfinite(st.linear_share));
}

TEST(DiagnoseLinearPart, TheMachineZeroAndTheDatumOffsetChangeNothing) {
  const Problem a = plate(structure, 0.0, 0.8, 7);
  const Problem b = plate(structure, -40.0, 0.8, 7, 150.0, -420.0);
  const Fitted fa = fit(a, smooth_dy(a, {0, 1}, 3)), fb = fit(b, smooth_dy(b, {0, 1}, 3));
  ASSERT_EQ(fa.st.linear_parts.size(), fb.st.linear_parts.size());
  for (std::size_t k = 0; k < fa.st.linear_parts.size(); ++k) {
    EXPECT_NEAR(fa.st.linear_parts[k].coef[0], fb.st.linear_parts[k].coef[0], 1e-8);
    EXPECT_NEAR(fa.st.linear_parts[k].stderr_[0], fb.st.linear_parts[k].stderr_[0], 1e-8);
  }
  EXPECT_NEAR(fa.st.linear_share, fb.st.linear_share, 1e-10);
}

}  // namespace
}  // namespace abbe::diagnose
