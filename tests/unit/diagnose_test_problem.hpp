#pragma once
// What every hand-made diagnosis Problem of the selection tests needs once
// its points and observations are in: the observed values, its one set, the
// measured directions and the travel box the candidates are normalised to.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/residuals.hpp"

namespace abbe::diagnose::test {

inline void finish_problem(Problem& pb, const std::vector<double>& y, const std::string& set,
                           const std::array<bool, 3>& directions, const Eigen::Vector3d& lo,
                           const Eigen::Vector3d& hi) {
  pb.y = Eigen::Map<const Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size()));
  pb.sets = {set};
  pb.direction_present = directions;
  for (int v = 0; v < 3; ++v) {
    pb.var_lo[static_cast<std::size_t>(v)] = lo[v];
    pb.var_hi[static_cast<std::size_t>(v)] = hi[v];
  }
  pb.travel_mid = 0.5 * (lo + hi);
  pb.travel_half = (0.5 * (hi - lo)).cwiseMax(1e-9);
}

// One point read along one direction u (a laser line, a probe): the point,
// its observation, the observed value and its file line.
inline void add_reading(Problem& pb, std::vector<double>& y, const PointContext& pc,
                        const Eigen::Vector3d& u, double value) {
  pb.obs.push_back({static_cast<std::uint32_t>(pb.points.size()), u});
  y.push_back(value);
  pb.points.push_back(pc);
  pb.lines.push_back(pb.points.size() + 1);
}

// A laser line along X: n readings at irregular positions x in [0, span]
// (drawn with position_seed), at machine position zero + x, read along X:
// dx = amplitude·sin(2πx/period + phase) + N(0, σ²) (noise_seed). The
// signal is a function of x, so another zero shifts only the phase a fit
// finds. One set "a".
inline Problem sine_line(double zero, double span, int n, double period, double amplitude,
                         double phase, double sigma, std::uint64_t position_seed,
                         std::uint64_t noise_seed) {
  Problem pb;
  std::vector<double> y;
  std::mt19937_64 at(position_seed), rng(noise_seed);
  std::uniform_real_distribution<double> u(0.0, span);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int k = 0; k < n; ++k) {
    const double x = u(at);
    PointContext pc;
    pc.p = pc.s = Eigen::Vector3d(zero + x, 0.0, 0.0);
    pc.dir = {1, 1, 1};
    pc.set = "a";
    add_reading(pb, y, pc, Eigen::Vector3d::UnitX(),
                amplitude * std::sin(6.283185307179586 * x / period + phase) + sigma * noise(rng));
  }
  finish_problem(pb, y, "a", {true, false, false}, Eigen::Vector3d(zero, 0.0, 0.0),
                 Eigen::Vector3d(zero + span, 0.0, 0.0));
  return pb;
}

// Three runs of one laser line along X (81 targets 10 mm apart, x from
// −900 mm, y = −250, z = −200), 20 min apart, each with an unknown offset
// of up to ±20 µm (the datum, one set per run "run0".."run2"):
// dX = amplitude·(1 − e^(−t/τ)) + N(0, σ²) (τ 0: no drift), t counted
// from the first reading; the readings' time stamps start at `t0`.
inline Problem drift_runs(double tau, double amplitude, double sigma, std::uint64_t seed,
                          double t0 = 0.0) {
  Problem pb;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  std::uniform_real_distribution<double> offset(-20.0, 20.0);
  std::vector<double> y;
  double t = 0.0;
  for (int set = 0; set < 3; ++set, t += 1200.0) {
    const double off = offset(rng);
    for (int i = 0; i <= 80; ++i, t += 10.0) {
      PointContext pc;
      pc.p = pc.s = Eigen::Vector3d(-900.0 + 10.0 * i, -250.0, -200.0);
      pc.t = t0 + t;
      pc.set = "run" + std::to_string(set);
      const double drift = tau > 0.0 ? amplitude * (1.0 - std::exp(-t / tau)) : 0.0;
      add_reading(pb, y, pc, Eigen::Vector3d::UnitX(), off + drift + noise(rng));
    }
  }
  finish_problem(pb, y, "run0", {true, false, false}, {-900, -250, -200}, {-100, -250, -200});
  pb.sets = {"run0", "run1", "run2"};
  return pb;
}

// Two laser lines, there and back, 11 targets 40 mm apart, 5 s apart: along
// X at y = 100 and along Y at x = 200, z = 0, one set. `line_only`: each
// point measured along its line (d_x on the X line, d_y on the Y line); else
// in X and Y both. Observed values 0.
inline Problem two_laser_lines(bool line_only) {
  Problem pb;
  std::vector<double> y;
  double t = 0.0;
  for (int a = 0; a < 2; ++a)
    for (int way : {1, -1})
      for (int k = 0; k <= 10; ++k) {
        const double s = 40.0 * (way > 0 ? k : 10 - k);
        PointContext pc;
        pc.p = a == 0 ? Eigen::Vector3d(s, 100.0, 0.0) : Eigen::Vector3d(200.0, s, 0.0);
        pc.s = pc.p;
        pc.dir = {a == 0 ? way : 1, a == 1 ? way : 1, 0};
        pc.t = t;
        t += 5.0;
        pc.set = "a";
        for (int i = 0; i < 2; ++i)
          if (!line_only || i == a) add_reading(pb, y, pc, Eigen::Vector3d::Unit(i), 0.0);
      }
  finish_problem(pb, y, "a", {true, true, false}, Eigen::Vector3d(0.0, 0.0, 0.0),
                 Eigen::Vector3d(400.0, 400.0, 0.0));
  pb.var_lo[3] = 0.0;
  pb.var_hi[3] = t;
  return pb;
}

// A term of `kind` on `axis`, acting in `direction` (-1: none).
inline Term make_term(TermKind kind, int axis, int direction) {
  Term t;
  t.kind = kind;
  t.axis = axis;
  t.direction = direction;
  return t;
}

// The problem's datum and one fixed candidate of `kind` (axis, direction).
inline CandidateSet datum_and(const Problem& pb, TermKind kind, int axis, int direction) {
  CandidateSet cs;
  cs.datum = build_candidates(pb, CandidateOptions{}).datum;
  cs.fixed = {make_term(kind, axis, direction)};
  return cs;
}

}  // namespace abbe::diagnose::test
