// The uncertainty of a prediction by Monte Carlo (GUM Supplement 1):
// zero in -> zero out, convergence, first-order propagation by hand, seeded
// reproducibility, and the rejection of bad uncertainty values.
#include "abbe/pipeline/prediction_uncertainty.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "abbe/io/input_error.hpp"
#include "abbe/machine/campaign_uncertainty.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/pipeline/predict.hpp"
#include "minimal_machine_text.hpp"
#include "model_test_machines.hpp"
#include "uncertainty_test_machines.hpp"

namespace abbe::pipeline {
namespace {

using machine::Machine;
using machine::MachineSpec;

using Row = test::McRow;
using test::McRun;

// Without --align (the overload without AlignOptions is the one `predict
// --uncertainty` calls: its rows are those of the aligned one with none).
McRun run(const Machine& m, const std::string& points_csv, std::size_t draws,
          std::uint64_t seed = 1, model::ModelKind kind = model::ModelKind::ae_arm) {
  McRun r = test::run_points(m, points_csv, draws, seed, kind, AlignOptions{});
  PredictOptions po;
  po.models = {kind};
  po.input = PredictInput::points;
  UncertaintyOptions uo;
  uo.draws = draws;
  uo.seed = seed;
  std::istringstream in(points_csv);
  std::size_t i = 0;
  predict_with_uncertainty(
      in, "points.csv", m, po, uo, {},
      [&](const model::EvalPoint&, std::size_t, const std::vector<model::Deviation>& devs,
          const std::vector<double>&, const std::vector<Eigen::Vector3d>& u) {
        EXPECT_EQ(r.rows.at(i).e, devs[0].e_um);
        EXPECT_EQ(r.rows.at(i).u, u[0]);
        ++i;
      });
  EXPECT_EQ(i, r.rows.size());
  return r;
}

using test::full_spec;
using test::kPoints;
using test::set_all_sources;

TEST(PredictionUncertainty, ZeroInputUncertaintyGivesZero) {
  MachineSpec spec = full_spec(true, 0.0);
  spec.uncertainty.given = true;  // given, every value zero
  const Machine m(spec);
  for (auto kind : {model::ModelKind::htm, model::ModelKind::ae_arm, model::ModelKind::dual}) {
    const McRun r = run(m, kPoints, 20, 1, kind);
    ASSERT_EQ(r.rows.size(), 8u);
    for (const Row& row : r.rows) {
      EXPECT_GT(row.e.norm(), 0.1);  // something is predicted
      EXPECT_EQ(row.u, Eigen::Vector3d::Zero());
    }
    for (const FigureUncertainty& f : r.prediction.uncertainty.models[0].all.figures) {
      EXPECT_EQ(f.u, 0.0);
      EXPECT_EQ(f.low, f.value);
      EXPECT_EQ(f.high, f.value);
    }
  }
}

TEST(PredictionUncertainty, DeviationsAreThoseOfPlainPredict) {
  MachineSpec spec = full_spec(true, 0.5);
  set_all_sources(spec.uncertainty);
  const Machine m(spec);
  const McRun r = run(m, kPoints, 10);
  PredictOptions po;
  po.input = PredictInput::points;
  std::istringstream in(kPoints);
  std::vector<Eigen::Vector3d> plain;
  const PredictionSummary s = predict(
      in, "points.csv", m, po, [&](const model::EvalPoint&, std::size_t, const ModelSet& models) {
        plain.push_back(models.deviations()[0].e_um);
      });
  ASSERT_EQ(plain.size(), r.rows.size());
  for (std::size_t i = 0; i < plain.size(); ++i) EXPECT_EQ(plain[i], r.rows[i].e);
  EXPECT_EQ(s.models[0].stats.max_um, r.prediction.summary.models[0].stats.max_um);
  EXPECT_EQ(r.prediction.uncertainty.models[0].all.figures[4].value, s.models[0].stats.max_um);
}

// N = 2000 against N = 4000 (the same seed: the first 2000 draws are shared):
// every u(dx), u(dy), u(dz) of every point and every summary u changes by
// less than 5 %.
TEST(PredictionUncertainty, DoublingTheDrawsChangesULessThanFivePercent) {
  MachineSpec spec = full_spec(true, 0.5);
  set_all_sources(spec.uncertainty);
  const Machine m(spec);
  const McRun a = run(m, kPoints, 2000);
  const McRun b = run(m, kPoints, 4000);
  auto u = [](const Row& r) { return r.u; };
  test::expect_converged(test::column(a.rows, u), test::column(b.rows, u),
                         a.prediction.uncertainty.models[0].all,
                         b.prediction.uncertainty.models[0].all);
}

// A linear case by hand: e_x = EXX(s_x) interpolated between two targets
// with per-target u, the laser constant and ppm; e_y = −EC0Y·y (squareness);
// e_x, e_z from EBX (two targets) with its component u (arm P − M fixed).
// First-order propagation gives u exactly; the Monte Carlo estimate with
// 20000 draws agrees within 3 %.
TEST(PredictionUncertainty, MatchesFirstOrderPropagationForALinearCase) {
  const std::string csv =
      "axis,component,position_mm,direction,value,uncertainty\n"
      "X,EXX,-1000,mean,1.0,0.4\n"
      "X,EXX,0,mean,-2.0,0.9\n"
      "X,EBX,-3000,mean,5.0,0\n"
      "X,EBX,3000,mean,5.0,0\n";
  MachineSpec spec = test::spec_with("w X' b Y Z t", csv, Eigen::Vector3d(-500, -250, -280), 130.0,
                                     Eigen::Vector3d(-800, -256, -478));
  spec.uncertainty.given = true;
  spec.uncertainty.laser_constant_um = 0.3;
  spec.uncertainty.laser_ppm = 2.0;
  spec.uncertainty.component[4] = 1.5;  // EBX, µrad
  spec.uncertainty.squareness_urad = {2.0, 0.0, 0.0};
  const Machine m(spec);
  const McRun r = run(m, "x,y,z\n-250,-100,-40\n-800,-400,-300\n", 20000);
  ASSERT_EQ(r.rows.size(), 2u);
  for (const Row& row : r.rows) {
    const double x = row.p.x(), y = row.p.y(), z = row.p.z();
    const double t = (x - (-1000.0)) / 1000.0;  // s_x = x (table axis)
    // EXX: independent per target (u_target and the laser constant), the
    // ppm part a scale of x − (−1000): ppm·10⁻³·(s − s₀) µm.
    const double u_exx2 = (1 - t) * (1 - t) * (0.4 * 0.4 + 0.3 * 0.3) +
                          t * t * (0.9 * 0.9 + 0.3 * 0.3) + std::pow(2.0e-3 * (x + 1000.0), 2);
    // EBX: e = θ × (P − M) → e_x = θ·(z − M_z)·10⁻³, e_z = −θ·(x − M_x)·10⁻³,
    // θ interpolated between its two targets (±3000 mm), each drawn on its
    // own: u(θ) = 1.5·√((1 − w)² + w²).
    const double w = (x + 3000.0) / 6000.0;
    const double u_theta = 1.5 * std::sqrt((1 - w) * (1 - w) + w * w);
    const double u_ebx_x = 1e-3 * u_theta * std::abs(z - (-478.0));
    const double u_ebx_z = 1e-3 * u_theta * std::abs(x - (-800.0));
    // EC0Y: e_x = −EC0Y·y·10⁻³.
    const double u_sq_x = 2.0e-3 * std::abs(y);
    const double ux = std::sqrt(u_exx2 + u_ebx_x * u_ebx_x + u_sq_x * u_sq_x);
    EXPECT_NEAR(row.u.x(), ux, 0.03 * ux) << x;
    EXPECT_EQ(row.u.y(), 0.0);
    EXPECT_NEAR(row.u.z(), u_ebx_z, 0.03 * u_ebx_z + 1e-12) << x;
  }
}

// Reflector-point uncertainty in ae-arm with a constant angle: e = θ × (P − M)
// is linear in M, u(e_x) = θ·u_M·10⁻³ (EBX moves e_x with M_z), u(e_z) the same.
TEST(PredictionUncertainty, ReflectorUncertaintyByHand) {
  const std::string csv = std::string(test::kHeader) + test::constant_rows("EBX", 20.0);
  MachineSpec spec = test::spec_with("w X' b Y Z t", csv, Eigen::Vector3d(-500, -250, -280), 130.0,
                                     Eigen::Vector3d(-800, -256, -478));
  spec.uncertainty.given = true;
  spec.uncertainty.reflector_mm = 3.0;
  const Machine m(spec);
  const McRun r = run(m, "x,y,z\n-100,-100,-100\n", 20000);
  const double expected = 20.0 * 3.0 * 1e-3;  // µrad × mm → nm → µm
  EXPECT_NEAR(r.rows[0].u.x(), expected, 0.03 * expected);
  EXPECT_EQ(r.rows[0].u.y(), 0.0);
  EXPECT_NEAR(r.rows[0].u.z(), expected, 0.03 * expected);
}

TEST(PredictionUncertainty, SeededAndReproducible) {
  MachineSpec spec = full_spec(true, 0.5);
  set_all_sources(spec.uncertainty);
  const Machine m(spec);
  const McRun a = run(m, kPoints, 50, 7);
  const McRun b = run(m, kPoints, 50, 7);
  const McRun c = run(m, kPoints, 50, 8);
  auto u = [](const Row& r) { return r.u; };
  test::expect_seeded(test::column(a.rows, u), test::column(b.rows, u), test::column(c.rows, u),
                      summary_json(a.prediction), summary_json(b.prediction));
}

TEST(PredictionUncertainty, NothingToPropagateIsAnError) {
  const Machine m(full_spec(false, 0.0));
  EXPECT_FALSE(machine::has_campaign_uncertainty(m));
  try {
    run(m, kPoints, 10);
    FAIL() << "accepted a machine without uncertainty";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "uncertainty");
    EXPECT_NE(e.message().find("nothing to propagate"), std::string::npos) << e.what();
  }
}

TEST(PredictionUncertainty, SummaryStatesTheCoverageFactor) {
  MachineSpec spec = full_spec(true, 0.5);
  const Machine m(spec);
  const McRun r = run(m, kPoints, 20);
  const std::string table = summary_table(r.prediction);
  EXPECT_NE(table.find("k = 2"), std::string::npos) << table;
  EXPECT_NE(table.find("per-target u"), std::string::npos) << table;
  const std::string json = summary_json(r.prediction);
  EXPECT_NE(json.find("\"coverage_factor\": 2.0"), std::string::npos) << json;
  for (const FigureUncertainty& f : r.prediction.uncertainty.models[0].all.figures) {
    EXPECT_DOUBLE_EQ(f.expanded, 2.0 * f.u);
    EXPECT_LE(f.low, f.high);
  }
}

// Bad uncertainty values are refused with the file, line and field.
const std::string& kDir = abbe::testing::kMachinesDir;
const std::string& kMachine = abbe::testing::kMinimalMachine;
using abbe::testing::AppendedKey;
using abbe::testing::AppendedKeyRejects;

INSTANTIATE_TEST_SUITE_P(
    Uncertainty, AppendedKeyRejects,
    ::testing::Values(AppendedKey{"uncertainty: {reflector_mm: -1}\n", 22,
                                  "uncertainty.reflector_mm", "negative"},
                      AppendedKey{"uncertainty: {reflector_mm: .nan}\n", 22,
                                  "uncertainty.reflector_mm", "finite"},
                      AppendedKey{"uncertainty:\n  laser: {constant_um: 0.1, ppm: -0.5}\n", 23,
                                  "uncertainty.laser.ppm", "negative"},
                      AppendedKey{"uncertainty:\n  laser: {constant_um: .inf}\n", 23,
                                  "uncertainty.laser.constant_um", "finite"},
                      AppendedKey{"uncertainty:\n  components: {EXX: 0.1, EYX: -2}\n", 23,
                                  "uncertainty.components.EYX", "negative"},
                      AppendedKey{"uncertainty:\n  components: {EC0Y: 0.1}\n", 23,
                                  "uncertainty.components.EC0Y", "not a component name"},
                      AppendedKey{"uncertainty:\n  squareness: {EC0Y: -1}\n", 23,
                                  "uncertainty.squareness.EC0Y", "negative"},
                      AppendedKey{"uncertainty:\n  laser_ppm: 1\n", 23, "uncertainty.laser_ppm",
                                  "unknown key"}));

TEST(PredictionUncertainty, GoodKeysParse) {
  const Machine m = Machine::parse(kMachine +
                                       "uncertainty:\n  laser: {constant_um: 0.1, ppm: 0.5}\n"
                                       "  components: {EYX: 0.3, EAZ: 1.2}\n"
                                       "  reflector_mm: 2\n  squareness: {EB0Z: 1.5}\n",
                                   "m.yaml", kDir);
  const machine::CampaignUncertainty& u = m.uncertainty();
  EXPECT_TRUE(u.given);
  EXPECT_EQ(u.laser_constant_um, 0.1);
  EXPECT_EQ(u.laser_ppm, 0.5);
  EXPECT_EQ(u.component[1], 0.3);          // EYX
  EXPECT_EQ(u.component[2 * 6 + 3], 1.2);  // EAZ
  EXPECT_EQ(u.reflector_mm, 2.0);
  EXPECT_EQ(u.squareness_urad[1], 1.5);
  EXPECT_TRUE(machine::has_campaign_uncertainty(m));
  // Old files: no key, nothing given.
  EXPECT_FALSE(Machine::parse(kMachine, "m.yaml", kDir).uncertainty().given);
}

TEST(PredictionUncertainty, TableColumnRejectsBadValues) {
  const std::string head = "axis,component,position_mm,direction,value,uncertainty\n";
  for (const auto& [row, says] : std::vector<std::pair<std::string, std::string>>{
           {"X,EXX,-10,mean,1.0,-0.2\n", "negative"},
           {"X,EXX,-10,mean,1.0,inf\n", "finite"},
           {"X,EXX,-10,mean,1.0,abc\n", "not a number"},
           {"X,EXX,-10,mean,1.0\n", "5 fields instead of 6"}}) {
    try {
      machine::ComponentTable::parse(head + row, "t.csv");
      FAIL() << "accepted " << row;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, "t.csv");
      EXPECT_EQ(e.where().line, 2u) << e.what();
      EXPECT_GT(e.where().column, 0u) << e.what();
      EXPECT_NE(e.message().find(says), std::string::npos) << e.what();
    }
  }
  const auto t = machine::ComponentTable::parse(head + "X,EXX,-10,mean,1.0,0.25\n", "t.csv");
  EXPECT_TRUE(t.has_uncertainty());
  EXPECT_EQ(t.series()[0].u, std::vector<double>{0.25});
  EXPECT_FALSE(
      machine::ComponentTable::parse(std::string(test::kHeader) + "X,EXX,-10,mean,1\n", "t.csv")
          .has_uncertainty());
}

}  // namespace
}  // namespace abbe::pipeline
