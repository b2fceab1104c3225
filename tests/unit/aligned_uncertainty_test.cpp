// The uncertainty of the part after its set-up (`predict --uncertainty N
// --align best-fit|datums`): every Monte Carlo draw is aligned again, so an
// uncertainty that only moves the part rigidly leaves the aligned deviation
// certain while the absolute one is not; the absolute u are those without
// --align; the aligned deviations those of predict_aligned; seeded,
// reproducible, convergent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/pipeline/aligned_prediction.hpp"
#include "abbe/pipeline/prediction_uncertainty.hpp"
#include "align_test_options.hpp"
#include "model_test_machines.hpp"
#include "uncertainty_test_machines.hpp"

namespace abbe::pipeline {
namespace {

using machine::Machine;
using machine::MachineSpec;

using test::McRun;

McRun run(const Machine& m, const std::string& points_csv, std::size_t draws, std::uint64_t seed,
          const AlignOptions& align) {
  return test::run_points(m, points_csv, draws, seed, model::ModelKind::ae_arm, align);
}

AlignOptions best_fit_options() { return test::best_fit_alignment(); }

// The faces of a block as CSV points (header on line 1): the bottom z = −400
// (lines 2–10), the front y = −500 (lines 11–16), the left x = −900 (lines
// 17–18), and three points inside (lines 19–21).
std::string block_points() {
  std::string csv = "x,y,z\n";
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) csv += fmt::format("{},{},-400\n", -800 + 300 * i, -450 + 150 * j);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 2; ++k) csv += fmt::format("{},-500,{}\n", -800 + 300 * i, -350 + 150 * k);
  for (int k = 0; k < 2; ++k) csv += fmt::format("-900,-300,{}\n", -350 + 150 * k);
  csv += "-500,-300,-200\n-200,-100,-100\n-700,-200,-250\n";
  return csv;
}

AlignOptions datum_options() { return test::datum_alignment("2-10", "11-16", "17-18"); }

// ae-arm with constant angles of every axis: e = Σ θ × (P − M), so the
// uncertainty of the reflector points M moves every point by the same
// vector −Σ θ × δM: a pure translation of the part. Its set-up (best fit or
// datums) takes it out in every draw: the aligned u vanish while the
// absolute u are θ·u_M·10⁻³ ≈ 0.06 µm.
TEST(AlignedUncertainty, RigidBodyOnlyUncertaintyLeavesTheAlignedPartCertain) {
  const std::string csv = std::string(test::kHeader) + test::constant_rows("EBX", 20.0) +
                          test::constant_rows("EAY", -15.0) + test::constant_rows("ECZ", 12.0);
  MachineSpec spec = test::spec_with("w X' b Y Z t", csv, Eigen::Vector3d(-500, -250, -280), 130.0,
                                     Eigen::Vector3d(-800, -256, -478));
  spec.uncertainty.given = true;
  spec.uncertainty.reflector_mm = 3.0;
  const Machine m(spec);
  for (const AlignOptions& align : {best_fit_options(), datum_options()}) {
    const McRun r = run(m, block_points(), 200, 1, align);
    ASSERT_EQ(r.rows.size(), 20u);
    for (const test::McRow& row : r.rows) {
      EXPECT_GT(row.u.norm(), 0.02) << to_string(align.method);
      EXPECT_LT(row.u_aligned.maxCoeff(), 1e-6) << to_string(align.method);
    }
    const ModelUncertainty& mu = r.prediction.uncertainty.models[0];
    EXPECT_GT(mu.all.figures[4].u, 0.005);  // max |d|
    for (const FigureUncertainty& f : mu.aligned.figures) EXPECT_LT(f.u, 1e-6);
  }
}

// The same draws with and without --align (same seed): the absolute u and
// figures do not change by the alignment.
TEST(AlignedUncertainty, AbsoluteUncertaintyIsThatWithoutAlign) {
  MachineSpec spec = test::full_spec(true, 0.5);
  test::set_all_sources(spec.uncertainty);
  const Machine m(spec);
  const McRun a = run(m, test::kPoints, 50, 5, best_fit_options());
  const McRun plain = run(m, test::kPoints, 50, 5, AlignOptions{});
  ASSERT_EQ(a.rows.size(), plain.rows.size());
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    EXPECT_EQ(a.rows[i].u, plain.rows[i].u);
    EXPECT_EQ(a.rows[i].e, plain.rows[i].e);
    EXPECT_EQ(plain.rows[i].u_aligned, Eigen::Vector3d::Zero());
  }
  for (std::size_t f = 0; f < kUncertainFigures; ++f)
    EXPECT_EQ(a.prediction.uncertainty.models[0].all.figures[f].u,
              plain.prediction.uncertainty.models[0].all.figures[f].u);
  EXPECT_EQ(plain.prediction.alignment.method, AlignMethod::none);
}

// The deviations after alignment and the alignment summary are those of
// predict_aligned.
TEST(AlignedUncertainty, AlignedDeviationsAreThoseOfPredictAligned) {
  MachineSpec spec = test::full_spec(true, 0.5);
  test::set_all_sources(spec.uncertainty);
  const Machine m(spec);
  for (const AlignOptions& align : {best_fit_options(), datum_options()}) {
    const McRun r = run(m, block_points(), 10, 1, align);
    PredictOptions po;
    po.input = PredictInput::points;
    std::istringstream in(block_points());
    std::vector<Eigen::Vector3d> aligned;
    const AlignedPrediction p =
        predict_aligned(in, "points.csv", m, po, align, {},
                        [&](const model::EvalPoint&, std::size_t,
                            const std::vector<model::Deviation>&, const std::vector<double>&,
                            const std::vector<Eigen::Vector3d>& a) { aligned.push_back(a[0]); });
    ASSERT_EQ(aligned.size(), r.rows.size());
    for (std::size_t i = 0; i < aligned.size(); ++i) EXPECT_EQ(aligned[i], r.rows[i].aligned);
    EXPECT_EQ(summary_json(p),
              summary_json(AlignedPrediction{r.prediction.summary, r.prediction.alignment}));
    EXPECT_EQ(r.prediction.uncertainty.models[0].aligned.figures[4].value,
              p.alignment.models[0].aligned.max_um);
  }
}

// N = 2000 against N = 4000 (the first 2000 draws shared): the u of the
// aligned deviation at every point, and of the aligned summary figures,
// change by less than 5 %.
TEST(AlignedUncertainty, DoublingTheDrawsChangesAlignedULessThanFivePercent) {
  MachineSpec spec = test::full_spec(true, 0.5);
  test::set_all_sources(spec.uncertainty);
  const Machine m(spec);
  const McRun a = run(m, test::kPoints, 2000, 1, best_fit_options());
  const McRun b = run(m, test::kPoints, 4000, 1, best_fit_options());
  auto u = [](const test::McRow& r) { return r.u_aligned; };
  test::expect_converged(test::column(a.rows, u), test::column(b.rows, u),
                         a.prediction.uncertainty.models[0].aligned,
                         b.prediction.uncertainty.models[0].aligned);
}

TEST(AlignedUncertainty, SeededAndReproducible) {
  MachineSpec spec = test::full_spec(true, 0.5);
  test::set_all_sources(spec.uncertainty);
  const Machine m(spec);
  const McRun a = run(m, block_points(), 40, 7, datum_options());
  const McRun b = run(m, block_points(), 40, 7, datum_options());
  const McRun c = run(m, block_points(), 40, 8, datum_options());
  auto u = [](const test::McRow& r) { return r.u_aligned; };
  test::expect_seeded(test::column(a.rows, u), test::column(b.rows, u), test::column(c.rows, u),
                      summary_json(a.prediction), summary_json(b.prediction));
}

TEST(AlignedUncertainty, SummaryCarriesTheAlignedFigures) {
  MachineSpec spec = test::full_spec(true, 0.5);
  const Machine m(spec);
  const McRun r = run(m, test::kPoints, 20, 1, best_fit_options());
  const std::string table = summary_table(r.prediction);
  EXPECT_NE(table.find("aligned by best-fit"), std::string::npos) << table;
  EXPECT_NE(table.find("          aligned "), std::string::npos) << table;
  const std::string json = summary_json(r.prediction);
  EXPECT_NE(json.find("\"alignment\": {"), std::string::npos) << json;
  const std::size_t u = json.find("\"uncertainty\": {");
  ASSERT_NE(u, std::string::npos) << json;
  EXPECT_NE(json.find("\"aligned\": {", u), std::string::npos) << json;
}

// A part that does not define its set-up is refused as with predict_aligned.
TEST(AlignedUncertainty, CollinearPartIsRefused) {
  MachineSpec spec = test::full_spec(true, 0.5);
  const Machine m(spec);
  EXPECT_THROW(
      run(m, "x,y,z\n-100,-100,-100\n-200,-100,-100\n-300,-100,-100\n", 5, 1, best_fit_options()),
      InputError);
}

}  // namespace
}  // namespace abbe::pipeline
