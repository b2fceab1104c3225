// The predict report with the part's set-up (`abbe report predict --align
// best-fit|datums [--uncertainty N]`): the deviation after alignment of the
// kept points is that of `predict --align` (and its u that of `predict
// --uncertainty N --align`) at the same points, the page shows it beside
// the absolute one (a plot per model and the part table), and without
// --align nothing of it appears.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/pipeline/aligned_prediction.hpp"
#include "abbe/pipeline/prediction_uncertainty.hpp"
#include "abbe/report/html_page.hpp"
#include "abbe/report/predict_section.hpp"
#include "abbe/report/predicted_path.hpp"
#include "align_test_options.hpp"
#include "rect_program.hpp"
#include "report_test_prediction.hpp"

namespace abbe::report {
namespace {

using test::kPlainMachine;
using test::kUncertainMachine;
const char* const kProgram = test::kRectProgram;
const std::vector<model::ModelKind> kModels{model::ModelKind::htm, model::ModelKind::ae_arm};

pipeline::AlignOptions best_fit() { return test::best_fit_alignment(); }

// The rectangle's bottom (lines 5–8, z = −280) is the primary plane, its
// first side (line 5, along X) the secondary line, line 6 the tertiary point.
pipeline::AlignOptions datums() { return test::datum_alignment("5-8", "5", "6"); }

PredictedPath predicted(const std::string& machine_file, const pipeline::AlignOptions& align,
                        std::size_t draws, std::size_t max_points = 20000) {
  return test::predict_rect(machine_file, align, draws, max_points);
}

std::string page_of(const PredictedPath& r) { return test::rect_page(r); }

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::ptrdiff_t matches(const std::string& text, const std::string& pattern) {
  const std::regex re(pattern);
  return std::distance(std::sregex_iterator(text.begin(), text.end(), re), std::sregex_iterator());
}

// Every point of `predict --align` for the rectangle: the aligned deviations
// per model.
struct AlignedAll {
  pipeline::AlignedPrediction prediction;
  std::vector<std::vector<Eigen::Vector3d>> aligned{2};
};

AlignedAll predict_aligned_all(const std::string& machine_file,
                               const pipeline::AlignOptions& align) {
  const machine::Machine m = machine::Machine::load(machine_file);
  pipeline::PredictOptions po;
  po.models = kModels;
  std::istringstream in(kProgram);
  AlignedAll all;
  all.prediction = pipeline::predict_aligned(
      in, "rect.ngc", m, po, align, {},
      [&](const model::EvalPoint&, std::size_t, const std::vector<model::Deviation>&,
          const std::vector<double>&, const std::vector<Eigen::Vector3d>& a) {
        for (std::size_t k = 0; k < 2; ++k) all.aligned[k].push_back(a[k]);
      });
  return all;
}

TEST(ReportAlignment, KeptPointsCarryTheAlignedDeviationOfPredict) {
  for (const pipeline::AlignOptions& align : {best_fit(), datums()}) {
    const PredictedPath r = predicted(kPlainMachine, align, 0, 16);
    ASSERT_TRUE(r.has_alignment());
    EXPECT_FALSE(r.has_uncertainty());
    ASSERT_GT(r.stride, 1u);  // thinned: the kept points are a subset
    const AlignedAll all = predict_aligned_all(kPlainMachine, align);
    ASSERT_EQ(all.aligned[0].size(), r.total_points);
    ASSERT_EQ(r.alignment.models.size(), 2u);
    EXPECT_EQ(r.alignment.method, align.method);
    EXPECT_EQ(r.alignment.part_points, all.prediction.alignment.part_points);
    for (std::size_t k = 0; k < 2; ++k) {
      ASSERT_EQ(r.aligned_um[k].size(), r.index.size());
      double moved = 0.0;  // the set-up changes the deviation
      for (std::size_t i = 0; i < r.index.size(); ++i) {
        EXPECT_EQ(r.aligned_um[k][i], all.aligned[k][r.index[i]]);
        moved = std::max(moved, (r.aligned_um[k][i] - r.deviation_um[k][i]).norm());
      }
      EXPECT_GT(moved, 0.1);
      const pipeline::ModelAlignment& a = r.alignment.models[k];
      const pipeline::ModelAlignment& b = all.prediction.alignment.models[k];
      EXPECT_EQ(a.kind, kModels[k]);
      EXPECT_EQ(a.aligned.max_um, b.aligned.max_um);
      EXPECT_EQ(a.aligned.rms_um(), b.aligned.rms_um());
      EXPECT_EQ(a.absolute.max_um, b.absolute.max_um);
      EXPECT_EQ(a.rotation_urad, b.rotation_urad);
      // The part is the cutting points: its absolute figures are the cutting row's.
      EXPECT_EQ(a.absolute.points, r.cutting_stats[k].points);
      EXPECT_EQ(a.absolute.max_um, r.cutting_stats[k].max_um);
    }
  }
}

TEST(ReportAlignment, WithUncertaintyKeptPointsCarryTheAlignedUOfPredict) {
  const PredictedPath r = predicted(kUncertainMachine, best_fit(), 20, 16);
  ASSERT_TRUE(r.has_alignment());
  ASSERT_TRUE(r.has_uncertainty());
  ASSERT_EQ(r.u_aligned_um.size(), 2u);
  // predict --uncertainty --align with the same draws, every point.
  const machine::Machine m = machine::Machine::load(kUncertainMachine);
  pipeline::PredictOptions po;
  po.models = kModels;
  pipeline::UncertaintyOptions uo;
  uo.draws = 20;
  uo.seed = 4;
  std::istringstream in(kProgram);
  std::vector<std::vector<Eigen::Vector3d>> a(2), u(2), ua(2);
  const pipeline::UncertainPrediction p = pipeline::predict_with_uncertainty(
      in, "rect.ngc", m, po, uo, best_fit(), {},
      [&](const model::EvalPoint&, std::size_t, const std::vector<model::Deviation>&,
          const std::vector<double>&, const std::vector<Eigen::Vector3d>& al,
          const std::vector<Eigen::Vector3d>& ul, const std::vector<Eigen::Vector3d>& ual) {
        for (std::size_t k = 0; k < 2; ++k) {
          a[k].push_back(al[k]);
          u[k].push_back(ul[k]);
          ua[k].push_back(ual[k]);
        }
      });
  ASSERT_EQ(a[0].size(), r.total_points);
  for (std::size_t k = 0; k < 2; ++k) {
    ASSERT_EQ(r.u_aligned_um[k].size(), r.index.size());
    double largest = 0.0;
    for (std::size_t i = 0; i < r.index.size(); ++i) {
      EXPECT_EQ(r.aligned_um[k][i], a[k][r.index[i]]);
      EXPECT_EQ(r.u_um[k][i], u[k][r.index[i]]);
      EXPECT_EQ(r.u_aligned_um[k][i], ua[k][r.index[i]]);
      largest = std::max(largest, r.u_aligned_um[k][i].maxCoeff());
    }
    EXPECT_GT(largest, 0.0);
    for (std::size_t f = 0; f < pipeline::kUncertainFigures; ++f)
      EXPECT_EQ(r.uncertainty.models[k].aligned.figures[f].expanded,
                p.uncertainty.models[k].aligned.figures[f].expanded);
  }
  // The absolute u are those of the report without --align.
  const PredictedPath plain = predicted(kUncertainMachine, {}, 20, 16);
  ASSERT_FALSE(plain.has_alignment());
  EXPECT_EQ(plain.u_um, r.u_um);
}

TEST(ReportAlignment, PageShowsTheAlignedDeviationBesideTheAbsolute) {
  const PredictedPath r = predicted(kPlainMachine, best_fit(), 0);
  const std::string html = page_of(r);
  for (const char* model : {"htm", "ae-arm"}) {
    EXPECT_EQ(count(html, fmt::format("id=\"deviation-{}\"", model)), 1u);
    EXPECT_EQ(count(html, fmt::format("id=\"aligned-deviation-{}\"", model)), 1u);
    EXPECT_NE(html.find(fmt::format("Deviation after best-fit alignment, {} model", model)),
              std::string::npos);
  }
  // The aligned plot follows its model's absolute one.
  EXPECT_LT(html.find("id=\"deviation-ae-arm\""), html.find("id=\"aligned-deviation-ae-arm\""));
  EXPECT_NE(html.find("id=\"part-table\""), std::string::npos);
  EXPECT_NE(html.find("ae-arm after best-fit alignment: P = ("), std::string::npos);  // hover
  EXPECT_EQ(count(html, "class=\"band\""), 0u);
  // Per model an absolute and an aligned row; the aligned row's max |d| is
  // the set-up's, the absolute row's that of the cutting points.
  const pipeline::ModelAlignment& ae = r.alignment.models[1];
  EXPECT_NE(
      html.find(fmt::format("<td>ae-arm</td><td>absolute</td><td>{}</td>", ae.absolute.points)),
      std::string::npos);
  const std::string aligned_row = fmt::format(
      "<td>ae-arm</td><td>after alignment</td><td>{}</td><td>{:.3f}</td><td>{:.3f}</td><td>{:."
      "3f}</td><td>{:.3f}</td><td>{:.3f}</td>",
      ae.aligned.points, ae.aligned.max_abs_um.x(), ae.aligned.max_abs_um.y(),
      ae.aligned.max_abs_um.z(), ae.aligned.rms_um(), ae.aligned.max_um);
  EXPECT_NE(html.find(aligned_row), std::string::npos) << aligned_row;
  EXPECT_LT(ae.aligned.rms_um(), ae.absolute.rms_um());

  // Datums: named in the titles and the caption.
  const std::string d = page_of(predicted(kPlainMachine, datums(), 0));
  EXPECT_NE(d.find("Deviation after datum (3-2-1) alignment, htm model"), std::string::npos);
  EXPECT_NE(d.find("from the primary ("), std::string::npos);
}

TEST(ReportAlignment, WithUncertaintyThePageDrawsTheAlignedBand) {
  const std::string html = page_of(predicted(kUncertainMachine, best_fit(), 20));
  // One band per component in each model's absolute and aligned plot.
  EXPECT_EQ(count(html, "<polygon class=\"band\""), 12u);
  EXPECT_EQ(count(html, "± U (k = 2)"), 4u);  // the legends
  // The part table: absolute and aligned rows of both models, every figure ± U.
  EXPECT_EQ(matches(html,
                    "<td>(htm|ae-arm)</td><td>(absolute|after alignment)</td><td>[0-9]+</td>"
                    "(<td>[0-9]+\\.[0-9]{3} ± [0-9]+\\.[0-9]{3}</td>){5}"),
            4);
  EXPECT_NE(html.find("with its band ± U from the draws"), std::string::npos);
}

TEST(ReportAlignment, WithoutAlignNothingOfItAppears) {
  const PredictedPath r = predicted(kUncertainMachine, {}, 5);
  EXPECT_FALSE(r.has_alignment());
  EXPECT_TRUE(r.u_aligned_um.empty());
  const std::string html = page_of(r);
  EXPECT_EQ(html.find("aligned-deviation"), std::string::npos);
  EXPECT_EQ(html.find("part-table"), std::string::npos);
  EXPECT_EQ(count(html, "<polygon class=\"band\""), 6u);
}

TEST(ReportAlignment, APartThatCannotBeAlignedIsAnInputError) {
  pipeline::AlignOptions a = datums();
  a.tertiary = pipeline::LineSet::parse("900", "--datum-tertiary");  // no such line
  EXPECT_THROW(predicted(kPlainMachine, a, 0), InputError);
}

}  // namespace
}  // namespace abbe::report
