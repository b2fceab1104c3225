// PredictedPath and the predict report: the statistics agree with the error
// model evaluated point by point, thinning keeps the statistics of every
// point, the page contains the expected plots.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <sstream>

#include "abbe/io/input_error.hpp"
#include "abbe/io/measured_data.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/report/compensate_section.hpp"
#include "abbe/report/diagnose_section.hpp"
#include "abbe/report/html_page.hpp"
#include "abbe/report/predict_section.hpp"
#include "abbe/report/predicted_path.hpp"
#include "rect_program.hpp"

namespace abbe::report {
namespace {

const std::string kMachine = std::string(ABBE_TEST_DATA_DIR) + "/machines/sample.yaml";

const char* const kProgram = test::kRectProgram;

TEST(ReportPredict, StatisticsMatchTheModelPointByPoint) {
  const machine::Machine m = machine::Machine::load(kMachine);
  PredictPathOptions o;
  o.models = {model::ModelKind::htm, model::ModelKind::ae_arm};
  std::istringstream in(kProgram);
  const PredictedPath r = predict_program(m, in, "rect.ngc", o);
  EXPECT_EQ(r.stride, 1u);
  ASSERT_EQ(r.nominal.size(), r.total_points);
  // Path length: the sum of the steps; the four cuts (lines 5-8) are 1000 mm
  // in 5 mm steps.
  double length = 0.0;
  for (std::size_t i = 1; i < r.nominal.size(); ++i)
    length += (r.nominal[i] - r.nominal[i - 1]).norm();
  EXPECT_NEAR(r.path_length.back(), length, 1e-9);
  const auto first_cut = static_cast<std::size_t>(
      std::find(r.line.begin(), r.line.end(), std::size_t{5}) - r.line.begin());
  ASSERT_LT(first_cut, r.line.size());
  EXPECT_NEAR(r.path_length.back() - r.path_length[first_cut - 1], 1000.0, 1e-9);
  EXPECT_EQ(r.total_points - first_cut, 200u);
  EXPECT_EQ(r.line.back(), 8u);
  EXPECT_EQ(r.source.at(5), "G1 X-650 F1000");

  for (std::size_t k = 0; k < 2; ++k) {
    const model::ErrorModel em(m, o.models[k]);
    model::ModelData data;
    double max_d = 0.0;
    for (std::size_t i = 0; i < r.nominal.size(); ++i) {
      max_d = std::max(max_d, r.deviation_um[k][i].norm());
    }
    EXPECT_DOUBLE_EQ(r.stats[k].max_um, max_d);
    EXPECT_GT(r.stats[k].max_um, 0.0);
    // One point recomputed independently (direction of motion: -X).
    model::EvalPoint p;
    p.p = r.nominal[first_cut + 30];  // on the first cut along −X
    p.tool_length = 200.0;
    p.dir = {-1, -1, -1};  // every axis last moved towards −
    const Eigen::Vector3d e = em.evaluate(p, data).e_um;
    EXPECT_NEAR((e - r.deviation_um[k][first_cut + 30]).norm(), 0.0, 1e-9) << k;
  }
  // htm and ae-arm differ on this machine (reflectors far from machine zero).
  EXPECT_GT(std::abs(r.stats[0].max_um - r.stats[1].max_um), 0.1);
}

TEST(ReportPredict, ThinningKeepsStatisticsOfAllPointsAndTheExtremes) {
  const machine::Machine m = machine::Machine::load(kMachine);
  PredictPathOptions full, thin;
  thin.max_points = 40;
  std::istringstream a(kProgram), b(kProgram);
  const PredictedPath rf = predict_program(m, a, "rect.ngc", full);
  const PredictedPath rt = predict_program(m, b, "rect.ngc", thin);
  EXPECT_EQ(rt.total_points, rf.total_points);
  EXPECT_GT(rt.stride, 1u);
  // Every stride-th point, plus at most one extreme per stretch.
  const std::size_t regular = (rf.total_points + rt.stride - 1) / rt.stride;
  EXPECT_LE(regular, 40u);
  EXPECT_GE(rt.nominal.size(), regular);
  EXPECT_LE(rt.nominal.size(), 2 * regular);
  EXPECT_DOUBLE_EQ(rt.stats[0].max_um, rf.stats[0].max_um);
  EXPECT_DOUBLE_EQ(rt.stats[0].rms_um, rf.stats[0].rms_um);
  ASSERT_EQ(rt.index.size(), rt.nominal.size());
  std::size_t n_regular = 0;
  for (std::size_t i = 0; i < rt.nominal.size(); ++i) {
    const std::size_t j = rt.index[i];
    if (i > 0) {
      EXPECT_GT(j, rt.index[i - 1]);  // in path order
    }
    if (j % rt.stride == 0) {
      EXPECT_EQ(j, n_regular * rt.stride);
      ++n_regular;
    } else {  // an extreme: larger than the regular point of its stretch
      EXPECT_GT(rt.deviation_um[0][i].norm(), rf.deviation_um[0][j - j % rt.stride].norm());
    }
    EXPECT_EQ(rt.nominal[i], rf.nominal[j]);
    EXPECT_DOUBLE_EQ(rt.path_length[i], rf.path_length[j]);
    EXPECT_EQ(rt.deviation_um[0][i], rf.deviation_um[0][j]);
  }
  EXPECT_EQ(n_regular, regular);
  // The peak of |d| is drawn: the kept points hold the largest deviation.
  double kept_max = 0.0;
  for (const auto& d : rt.deviation_um[0]) kept_max = std::max(kept_max, d.norm());
  EXPECT_DOUBLE_EQ(kept_max, rf.stats[0].max_um);

  // Several models: each model's largest |d| is kept.
  PredictPathOptions two = thin;
  two.models = {model::ModelKind::htm, model::ModelKind::ae_arm};
  std::istringstream c(kProgram);
  const PredictedPath r2 = predict_program(m, c, "rect.ngc", two);
  EXPECT_LE(r2.nominal.size(), 3 * ((r2.total_points + r2.stride - 1) / r2.stride));
  for (std::size_t k = 0; k < 2; ++k) {
    double mx = 0.0;
    for (const auto& d : r2.deviation_um[k]) mx = std::max(mx, d.norm());
    EXPECT_DOUBLE_EQ(mx, r2.stats[k].max_um) << k;
  }
  for (std::size_t i = 1; i < r2.index.size(); ++i) EXPECT_GT(r2.index[i], r2.index[i - 1]);
}

TEST(ReportPredict, BadProgramNamesFileAndLine) {
  const machine::Machine m = machine::Machine::load(kMachine);
  std::istringstream in("G1 X0 F100\nG1 X1 Q\n");
  try {
    predict_program(m, in, "bad.ngc", PredictPathOptions{});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "bad.ngc");
    EXPECT_EQ(e.where().line, 2u);
  }
}

TEST(ReportPredict, PageHasEveryPlotAndTheSummary) {
  const machine::Machine m = machine::Machine::load(kMachine);
  PredictPathOptions o;
  o.models = {model::ModelKind::htm, model::ModelKind::ae_arm, model::ModelKind::dual};
  std::istringstream in(kProgram);
  const PredictedPath r = predict_program(m, in, "rect.ngc", o);
  const double k = auto_exaggeration(r);
  // The largest deviation drawn is about 4 % of the 300 mm extent.
  Eigen::Vector3d lo = r.nominal[0], hi = lo;
  for (const auto& p : r.nominal) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double extent = (hi - lo).maxCoeff();
  const double drawn =
      k * 1e-3 * std::max({r.stats[0].max_um, r.stats[1].max_um, r.stats[2].max_um});
  EXPECT_GT(drawn, 0.004 * extent);
  EXPECT_LE(drawn, 0.04 * extent + 1e-9);

  HtmlPage page("t");
  render_predict_report(page, r, 0.0);
  const std::string html = page.render();
  for (const char* id : {"toolpath-3d", "toolpath-3d-data", "toolpath-3d-tol", "deviation-models",
                         "deviation-htm", "deviation-ae-arm", "deviation-dual", "summary-table"})
    EXPECT_NE(html.find(std::string("id=\"") + id + "\""), std::string::npos) << id;
  EXPECT_NE(html.find("line 5: G1 X-650 F1000"), std::string::npos);
  EXPECT_NE(html.find("\"5\":\"G1 X-650 F1000\""), std::string::npos);  // 3-D view hover text
  EXPECT_FALSE(std::regex_search(html, std::regex("\\bnan\\b|\\binf\\b", std::regex::icase)));
}

TEST(ReportPredict, IsometricDrawing) {
  // Z is straight up, X and Y go down to the left and right at 30°.
  EXPECT_NEAR(isometric({0, 0, 1}).x(), 0.0, 1e-12);
  EXPECT_NEAR(isometric({0, 0, 1}).y(), 1.0, 1e-12);
  EXPECT_LT(isometric({1, 0, 0}).x(), 0.0);
  EXPECT_GT(isometric({0, 1, 0}).x(), 0.0);
  EXPECT_NEAR(isometric({1, 0, 0}).y(), -0.5, 1e-12);
  EXPECT_NEAR(isometric({1, 0, 0}).norm(), 1.0, 1e-12);
}

}  // namespace
}  // namespace abbe::report

namespace abbe::report {
namespace {

TEST(ReportCompensate, UncompensatedProgramIsAsFarAsItsPredictedDeviationAllows) {
  // The "compensated" program is the original itself: every predicted point
  // lies at most |d| from the nominal path (the nearest point can only be
  // closer than the point it came from), and feed points are not on it.
  const machine::Machine m = machine::Machine::load(kMachine);
  PredictPathOptions o;
  const CompensationComparison c = compare_compensation(m, kProgram, "a.ngc", kProgram, "b.ngc", o);
  ASSERT_EQ(c.residual_um.size(), c.compensated.nominal.size());
  ASSERT_EQ(c.compensated.nominal.size(), c.original.nominal.size());
  double max_r = 0.0;
  for (std::size_t i = 0; i < c.residual_um.size(); ++i) {
    EXPECT_LE(c.residual_um[i].norm(), c.original.deviation_um[0][i].norm() + 1e-6) << i;
    max_r = std::max(max_r, c.residual_um[i].norm());
  }
  EXPECT_DOUBLE_EQ(c.residual_max_um, max_r);
  EXPECT_GT(c.residual_rms_um, 1.0);
  HtmlPage page("c");
  render_compensate_report(page, c, 0.0);
  const std::string html = page.render();
  for (const char* id :
       {"compensate-table", "compensate-iso", "compensate-xy", "compensate-deviation"})
    EXPECT_NE(html.find(std::string("id=\"") + id + "\""), std::string::npos) << id;
}

}  // namespace
}  // namespace abbe::report

namespace abbe::report {
namespace {

TEST(ReportDiagnose, ResidualAfterTheExtensionIsTheExtendedModels) {
  // The sample machine's measured grid (SYNTHETIC, abbe simulate measure):
  // the residual rebuilt with the overlay is what the diagnosis reports for
  // the extended model, and smaller than before.
  const std::string dir = std::string(ABBE_SOURCE_DIR) + "/machines/sample/";
  const machine::Machine m = machine::Machine::load(dir + "machine.yaml");
  const io::MeasuredData data = io::load_measured_data(dir + "measured-grid.csv");
  const DiagnosisForReport r = diagnose_for_report(m, data, diagnose::DiagnoseOptions{});
  ASSERT_EQ(r.before.y.size(), r.after.y.size());
  const auto before = diagnose::residual_stats(r.before, r.before.y);
  const auto after = diagnose::residual_stats(r.after, r.after.y);
  EXPECT_NEAR(before.rms_um, r.diagnosis.baseline.rms_um, 1e-9);
  EXPECT_NEAR(after.rms_um, r.diagnosis.extended.rms_um, 0.02 * r.diagnosis.extended.rms_um);
  EXPECT_LT(after.rms_um, before.rms_um);
  HtmlPage page("d");
  render_diagnose_report(page, r);
  const std::string html = page.render();
  for (const char* id : {"diagnose-models", "diagnose-effects", "residual-x", "residual-y",
                         "residual-z", "residual-t"})
    EXPECT_NE(html.find(std::string("id=\"") + id + "\""), std::string::npos) << id;
}

}  // namespace
}  // namespace abbe::report
