#pragma once
// The machines and points of the Monte Carlo uncertainty tests
// (prediction_uncertainty_test.cpp, aligned_uncertainty_test.cpp).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "abbe/machine/campaign_uncertainty.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/pipeline/prediction_uncertainty.hpp"
#include "model_test_machines.hpp"

namespace abbe::test {

// One point of a Monte Carlo run: nominal, deviation, deviation after the
// set-up (zero without --align), and their standard uncertainties (µm).
struct McRow {
  Eigen::Vector3d p, e, aligned, u, u_aligned;
};

struct McRun {
  pipeline::UncertainPrediction prediction;
  std::vector<McRow> rows;
};

// predict_with_uncertainty of one model at the points of a CSV.
inline McRun run_points(const machine::Machine& m, const std::string& points_csv, std::size_t draws,
                        std::uint64_t seed, model::ModelKind kind,
                        const pipeline::AlignOptions& align) {
  pipeline::PredictOptions po;
  po.models = {kind};
  po.input = pipeline::PredictInput::points;
  pipeline::UncertaintyOptions uo;
  uo.draws = draws;
  uo.seed = seed;
  std::istringstream in(points_csv);
  McRun r;
  r.prediction = pipeline::predict_with_uncertainty(
      in, "points.csv", m, po, uo, align, {},
      [&](const model::EvalPoint& p, std::size_t, const std::vector<model::Deviation>& devs,
          const std::vector<double>&, const std::vector<Eigen::Vector3d>& aligned,
          const std::vector<Eigen::Vector3d>& u, const std::vector<Eigen::Vector3d>& u_aligned) {
        r.rows.push_back({p.p, devs[0].e_um, aligned[0], u[0], u_aligned[0]});
      });
  return r;
}

// A table with every component of every axis (values of a few µm/µrad) and
// per-target uncertainties; reflectors away from the points.
inline std::string full_table(bool with_u, double u_target) {
  std::string csv =
      with_u ? "axis,component,position_mm,direction,value,uncertainty\n" : std::string(kHeader);
  int k = 0;
  for (char a : {'X', 'Y', 'Z'})
    for (char d : {'X', 'Y', 'Z', 'A', 'B', 'C'})
      for (int i = 0; i <= 6; ++i, ++k) {
        const double v = 3.0 * std::sin(0.7 * k);
        csv += fmt::format("{},E{}{},{},mean,{:.6f}", a, d, a, -1200.0 + 400.0 * i, v);
        if (with_u) csv += fmt::format(",{}", u_target);
        csv += "\n";
      }
  return csv;
}

inline machine::MachineSpec full_spec(bool with_u, double u_target) {
  machine::MachineSpec spec =
      spec_with("w X' b Y Z t", full_table(with_u, u_target), Eigen::Vector3d(-500, -250, -280),
                130.0, Eigen::Vector3d(-800, -256, -478));
  spec.squareness = {14.0, -24.0, 13.0};
  return spec;
}

inline const char* kPoints =
    "x,y,z\n-100,-50,-30\n-300,-200,-250\n-650,-420,-120\n-900,-10,-400\n-480,-333,-333\n"
    "-20,-590,-10\n-777,-111,-222\n-250,-250,-250\n";

inline void set_all_sources(machine::CampaignUncertainty& u) {
  u.given = true;
  u.laser_constant_um = 0.2;
  u.laser_ppm = 1.0;
  u.component.fill(0.3);
  u.reflector_mm = 2.0;
  u.squareness_urad = {1.0, 1.5, 0.5};
}

// Convergence of the draws: N against 2N draws (the first N shared), every
// u of every point (`a`, `b`; each of 2N above 0.01 µm) and every summary u
// (`fa`, `fb`) change by less than 5 %.
inline void expect_converged(const std::vector<Eigen::Vector3d>& a,
                             const std::vector<Eigen::Vector3d>& b,
                             const pipeline::GroupUncertainty& fa,
                             const pipeline::GroupUncertainty& fb) {
  ASSERT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      ASSERT_GT(b[i][c], 0.01) << "point " << i << ", component " << c;
      worst = std::max(worst, std::abs(a[i][c] / b[i][c] - 1.0));
    }
  EXPECT_LT(worst, 0.05);
  for (std::size_t f = 0; f < pipeline::kUncertainFigures; ++f) {
    const double ua = fa.figures[f].u, ub = fb.figures[f].u;
    ASSERT_GT(ub, 0.0);
    EXPECT_LT(std::abs(ua / ub - 1.0), 0.05) << "figure " << f;
  }
}

// Seeded draws: the same seed gives the same u at every point (`a`, `b`)
// and the same summary; another seed (`c`) other u.
inline void expect_seeded(const std::vector<Eigen::Vector3d>& a,
                          const std::vector<Eigen::Vector3d>& b,
                          const std::vector<Eigen::Vector3d>& c, const std::string& summary_a,
                          const std::string& summary_b) {
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), c.size());
  bool differs = false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i], b[i]);
    differs = differs || a[i] != c[i];
  }
  EXPECT_TRUE(differs);
  EXPECT_EQ(summary_a, summary_b);
}

// One vector of every row: `of(row)`.
template <class Row, class Of>
std::vector<Eigen::Vector3d> column(const std::vector<Row>& rows, Of of) {
  std::vector<Eigen::Vector3d> out;
  for (const Row& r : rows) out.push_back(of(r));
  return out;
}

}  // namespace abbe::test
