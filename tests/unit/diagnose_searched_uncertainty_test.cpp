// The standard uncertainty of a searched parameter (searched_uncertainty.hpp):
// a cycle's period against the hand-computed Gauss–Newton value and against
// the scatter of the least-squares period over noise draws; zero amplitude
// → undetermined; the axis's zero does not change it; a drift's τ against
// its scatter; kinds without a searched parameter get none.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <iostream>
#include <random>

#include "abbe/diagnose/selection.hpp"
#include "diagnose_test_problem.hpp"
#include "src/diagnose/parameter_scan.hpp"
#include "src/diagnose/searched_uncertainty.hpp"

namespace abbe::diagnose::selection {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kPeriod = 13.37;  // mm
constexpr double kSpan = 800.0;    // mm

// 400 readings along X at fixed irregular positions in [zero, zero + 800];
// dx = amplitude·sin(2πx/P + 0.4) + N(0, σ²) (noise drawn with `seed`).
Problem line(double zero, double amplitude, double sigma, std::uint64_t seed) {
  return test::sine_line(zero, kSpan, 400, kPeriod, amplitude, 0.4, sigma, 5, seed);
}

// The fit the selection ends with: the datum's offset and the term's
// columns, least squares; returns the fitted term, X, (XᵀX)⁻¹ and σ̂².
struct Fitted {
  Term term;
  Mat X, inv;
  double s2 = 0.0;
};
Fitted fit(const Problem& pb, Term t) {
  const Mat C = term_columns(pb, t);
  Fitted f;
  f.X.resize(C.rows(), C.cols() + 1);
  f.X << Mat::Ones(C.rows(), 1), C;
  f.inv = (f.X.transpose() * f.X).inverse();
  const Vec beta = f.inv * (f.X.transpose() * pb.y);
  t.coef.assign(beta.data() + 1, beta.data() + beta.size());
  f.term = t;
  f.s2 = (pb.y - f.X * beta).squaredNorm() / static_cast<double>(C.rows() - f.X.cols());
  return f;
}

// A cycle or a drift of `axis` in its own direction, its searched
// parameter (period_mm, tau_s) set to `value`.
Term searched_term(TermKind kind, int axis, double value) {
  Term t;
  t.kind = kind;
  t.axis = axis;
  t.direction = axis;
  (kind == TermKind::cyclic ? t.period_mm : t.tau_s) = value;
  return t;
}
Term cycle(double period) { return searched_term(TermKind::cyclic, 0, period); }

// The least-squares period of one noise draw: the true one refined on the
// exact ΔRSS beside the datum.
double ls_period(const Problem& pb) {
  const auto n = pb.y.size();
  const Mat Q = Mat::Constant(n, 1, 1.0 / std::sqrt(static_cast<double>(n)));
  const Vec r = pb.y - Q * (Q.transpose() * pb.y);
  Cached c{cycle(kPeriod), term_columns(pb, cycle(kPeriod)), Mat(), Mat(), {}};
  c.CtC = c.C.transpose() * c.C;
  c.QtC = Q.transpose() * c.C;
  refine_period_exactly(pb, Q, r, 0.25 / kSpan, c);
  return c.term.period_mm;
}

// Over `draws` noise draws: the least-squares estimate θ̂ of each draw
// (`estimate`), its mean and scatter, and the mean of the uncertainty
// reported at θ̂ (the fitted term `at(θ̂)`).
struct Scatter {
  double mean = 0.0, sd = 0.0, reported = 0.0;
};
Scatter scatter_and_reported(int draws, const std::function<Problem(int)>& draw,
                             const std::function<double(const Problem&)>& estimate,
                             const std::function<Term(double)>& at) {
  double sum = 0.0, sum2 = 0.0, u_sum = 0.0;
  for (int k = 0; k < draws; ++k) {
    const Problem pb = draw(k);
    const double theta = estimate(pb);
    sum += theta;
    sum2 += theta * theta;
    const Fitted f = fit(pb, at(theta));
    u_sum += searched_parameter_stderr(pb, f.term, f.X, f.inv, f.s2);
  }
  Scatter sc;
  sc.mean = sum / draws;
  sc.sd = std::sqrt((sum2 - sum * sum / draws) / (draws - 1));
  sc.reported = u_sum / draws;
  return sc;
}

// Hand-computed: the derivative of Â·sin(2πs/P + φ̂) in P is
// −(2πÂ s/P²)·cos(2πs/P + φ̂); beside sin, cos and the offset what is left
// of it is, to O(1/n), its part in (s − s̄): ‖d⊥‖² ≈ (2πÂ/P²)²·Σ(s − s̄)²
// cos²(2πs/P + φ̂), and u(P) = σ̂/‖d⊥‖.
TEST(DiagnoseSearchedUncertainty, APeriodAgainstTheHandComputedValue) {
  const Problem pb = line(0.0, 3.0, 0.5, 1);
  const Fitted f = fit(pb, cycle(kPeriod));
  const double u = searched_parameter_stderr(pb, f.term, f.X, f.inv, f.s2);
  const double amp = std::hypot(f.term.coef[0], f.term.coef[1]);
  const double phase = std::atan2(f.term.coef[1], f.term.coef[0]);
  double mean = 0.0, ss = 0.0;
  for (const PointContext& pc : pb.points) mean += pc.s.x();
  mean /= static_cast<double>(pb.points.size());
  for (const PointContext& pc : pb.points) {
    const double c = std::cos(2.0 * kPi * pc.s.x() / kPeriod + phase);
    ss += (pc.s.x() - mean) * (pc.s.x() - mean) * c * c;
  }
  const double hand = std::sqrt(f.s2) / (2.0 * kPi * amp / (kPeriod * kPeriod) * std::sqrt(ss));
  EXPECT_NEAR(u / hand, 1.0, 0.01) << u << " vs " << hand;
}

// The scatter of the least-squares period over 200 noise draws agrees with
// the reported uncertainty (±15 %: the scatter's own relative error is
// 1/√(2·200) = 5 %).
TEST(DiagnoseSearchedUncertainty, APeriodsUncertaintyIsItsScatter) {
  const int draws = 200;
  const Scatter sc = scatter_and_reported(
      draws, [](int k) { return line(0.0, 2.0, 0.5, 100 + static_cast<std::uint64_t>(k)); },
      ls_period, cycle);
  std::cout << "period: scatter " << sc.sd << " mm, reported " << sc.reported << " mm\n";
  EXPECT_NEAR(sc.sd / sc.reported, 1.0, 0.15);
  EXPECT_NEAR(sc.mean, kPeriod, 3.0 * sc.sd / std::sqrt(draws));
}

// Zero in: no cycle, nothing fixes its period.
TEST(DiagnoseSearchedUncertainty, ZeroAmplitudeLeavesThePeriodUndetermined) {
  const Problem pb = line(0.0, 0.0, 0.0, 1);
  Fitted f = fit(pb, cycle(kPeriod));
  f.term.coef = {0.0, 0.0};
  EXPECT_TRUE(std::isinf(searched_parameter_stderr(pb, f.term, f.X, f.inv, 1.0)));
}

// The axis's zero is a free constant of the conventions: the same data at
// another zero give the same uncertainty.
TEST(DiagnoseSearchedUncertainty, TheAxisZeroDoesNotChangeIt) {
  double u[2];
  for (int k = 0; k < 2; ++k) {
    const Problem pb = line(k == 0 ? 0.0 : 512.5, 2.0, 0.5, 3);
    const Fitted f = fit(pb, cycle(kPeriod));
    u[k] = searched_parameter_stderr(pb, f.term, f.X, f.inv, f.s2);
  }
  EXPECT_NEAR(u[0] / u[1], 1.0, 1e-4);
}

// A drift's time constant: 1 µm·(1 − e^(−t/τ)) read every 10 s for two
// hours, τ = 1500 s; the reported u(τ) against the scatter of the
// least-squares τ (a fine scan) over 100 noise draws, ±25 %.
TEST(DiagnoseSearchedUncertainty, ADriftsTimeConstantIsItsScatter) {
  const double tau = 1500.0;
  auto drift_line = [&](std::uint64_t seed) {
    Problem pb;
    std::vector<double> y;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> n(0.0, 0.2);
    for (int k = 0; k < 720; ++k) {
      PointContext pc;
      pc.p = pc.s = Eigen::Vector3d(0.0, 0.0, 0.0);
      pc.t = 10.0 * k;
      pc.set = "a";
      test::add_reading(pb, y, pc, Eigen::Vector3d::UnitZ(),
                        1.0 * (1.0 - std::exp(-pc.t / tau)) + n(rng));
    }
    test::finish_problem(pb, y, "a", {false, false, true}, Eigen::Vector3d::Zero(),
                         Eigen::Vector3d::Zero());
    return pb;
  };
  auto drift = [](double t) { return searched_term(TermKind::thermal_drift, 2, t); };
  auto least_squares_tau = [&](const Problem& pb) {
    double best = tau, best_s2 = 1e300;
    for (double t = 900.0; t <= 2400.0; t += 2.0) {
      const double s2 = fit(pb, drift(t)).s2;
      if (s2 < best_s2) {
        best_s2 = s2;
        best = t;
      }
    }
    return best;
  };
  const Scatter sc = scatter_and_reported(
      100, [&](int k) { return drift_line(500 + static_cast<std::uint64_t>(k)); },
      least_squares_tau, drift);
  std::cout << "tau: scatter " << sc.sd << " s, reported " << sc.reported << " s\n";
  EXPECT_NEAR(sc.sd / sc.reported, 1.0, 0.25);
}

// A drift linear in time and a scale have no searched parameter.
TEST(DiagnoseSearchedUncertainty, KindsWithoutASearchedParameterGetNone) {
  const Problem pb = line(0.0, 2.0, 0.5, 3);
  Term scale;
  scale.kind = TermKind::scale;
  scale.axis = 0;
  scale.direction = 0;
  const Fitted f = fit(pb, scale);
  EXPECT_EQ(searched_parameter_stderr(pb, f.term, f.X, f.inv, f.s2), 0.0);
  Term linear;
  linear.kind = TermKind::thermal_drift;
  linear.axis = 0;
  linear.direction = 0;
  linear.tau_s = 0.0;
  linear.coef = {1.0};
  EXPECT_EQ(searched_parameter_stderr(pb, linear, f.X, f.inv, f.s2), 0.0);
}

}  // namespace
}  // namespace abbe::diagnose::selection
