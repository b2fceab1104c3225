// The predict report with the campaign's uncertainty (`abbe report predict
// --uncertainty N`): the u of the kept points are those of `predict
// --uncertainty` at the same points, the deviation plots carry the band
// d ± U (k = 2) and the summary the figures ± U; without it the page is the
// one the report made before the uncertainty existed (golden SHA-256).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "abbe/io/sha256.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/pipeline/prediction_uncertainty.hpp"
#include "abbe/report/html_page.hpp"
#include "abbe/report/line_plot.hpp"
#include "abbe/report/predict_section.hpp"
#include "abbe/report/predicted_path.hpp"
#include "rect_program.hpp"
#include "report_test_prediction.hpp"

namespace abbe::report {
namespace {

using test::kPlainMachine;
using test::kUncertainMachine;
const char* const kProgram = test::kRectProgram;

PredictedPath predicted(const std::string& machine_file, std::size_t draws,
                        std::size_t max_points = 20000) {
  return test::predict_rect(machine_file, {}, draws, max_points);
}

// The page without its footer (which names abbe's version).
std::string page_of(const PredictedPath& r) {
  std::string html = test::rect_page(r);
  const std::size_t footer = html.find("<footer id=\"provenance\">");
  EXPECT_NE(footer, std::string::npos);
  return html.substr(0, footer);
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// A number written as nan or inf (not the letters inside a word).
bool has_nan(const std::string& text) {
  return std::regex_search(text, std::regex("[^a-z](nan|inf)[^a-z]"));
}

// The SHA-256 of the page made by the report before --uncertainty existed
// (main at c313afb, made with its library), for the same program and machine.
TEST(ReportUncertainty, WithoutUncertaintyThePageIsUnchanged) {
  const PredictedPath r = predicted(kPlainMachine, 0);
  EXPECT_FALSE(r.has_uncertainty());
  const std::string html = page_of(r);
  EXPECT_EQ(count(html, "class=\"band\""), 0u);
  EXPECT_EQ(io::sha256_hex(html),
            "d709323bf6f5b56b3620a724fb9ba01770013a593b7d2edf86e21231ad528fe6");
}

TEST(ReportUncertainty, KeptPointsCarryTheUOfPredict) {
  const PredictedPath r = predicted(kUncertainMachine, 30, 16);
  ASSERT_TRUE(r.has_uncertainty());
  ASSERT_GT(r.stride, 1u);  // thinned: the kept points are a subset
  ASSERT_EQ(r.u_um.size(), 2u);
  // predict --uncertainty with the same draws, every point.
  const machine::Machine m = machine::Machine::load(kUncertainMachine);
  pipeline::PredictOptions po;
  po.models = r.models;
  pipeline::UncertaintyOptions uo;
  uo.draws = 30;
  uo.seed = 4;
  std::istringstream in(kProgram);
  std::vector<std::vector<Eigen::Vector3d>> all(2);
  const pipeline::UncertainPrediction p = pipeline::predict_with_uncertainty(
      in, "rect.ngc", m, po, uo, {},
      [&](const model::EvalPoint&, std::size_t, const std::vector<model::Deviation>&,
          const std::vector<double>&, const std::vector<Eigen::Vector3d>& u) {
        for (std::size_t k = 0; k < 2; ++k) all[k].push_back(u[k]);
      });
  ASSERT_EQ(all[0].size(), r.total_points);
  for (std::size_t k = 0; k < 2; ++k) {
    ASSERT_EQ(r.u_um[k].size(), r.index.size());
    for (std::size_t i = 0; i < r.index.size(); ++i) EXPECT_EQ(r.u_um[k][i], all[k][r.index[i]]);
    for (std::size_t f = 0; f < pipeline::kUncertainFigures; ++f)
      EXPECT_EQ(r.uncertainty.models[k].all.figures[f].expanded,
                p.uncertainty.models[k].all.figures[f].expanded);
  }
  double largest = 0.0;
  for (const auto& u : r.u_um[1]) largest = std::max(largest, u.maxCoeff());
  EXPECT_GT(largest, 0.01);
}

TEST(ReportUncertainty, PageDrawsTheBandAndTheFiguresWithU) {
  const PredictedPath r = predicted(kUncertainMachine, 20);
  const std::string html = page_of(r);
  // One band per component in each model's deviation plot.
  EXPECT_EQ(count(html, "<polygon class=\"band\""), 6u);
  EXPECT_EQ(count(html, "± U (k = 2)"), 2u);  // the legends
  EXPECT_NE(html.find("Monte Carlo (GUM Supplement 1: 20 draws, seed 4)"), std::string::npos);
  EXPECT_NE(html.find("u(d) = ("), std::string::npos);  // hover text
  // Every figure of the summary table: value ± U.
  const std::regex cell("<td>[0-9]+\\.[0-9]{3} ± [0-9]+\\.[0-9]{3}</td>");
  const auto cells =
      std::distance(std::sregex_iterator(html.begin(), html.end(), cell), std::sregex_iterator());
  EXPECT_EQ(cells, 2 * 3 * 5);  // models × (cutting, rapid, all) × figures
  EXPECT_FALSE(has_nan(html));
}

// The band of a LinePlot: one polygon along lo and back along hi, under
// the series; the range covers both edges; points where an edge is not
// finite are left out; its legend entry follows the series'.
TEST(ReportUncertainty, BandIsOnePolygon) {
  LinePlot plot;
  plot.id = "band-test";
  Band band;
  band.name = "the band";
  band.colour = "#123456";
  band.x = {0.0, 1.0, 2.0, 3.0};
  band.lo = {-1.0, -2.0, NAN, -1.0};
  band.hi = {1.0, 50.0, 1.0, 1.0};
  plot.bands.push_back(band);
  Series line;
  line.name = "line";
  line.x = {0.0, 3.0};
  line.y = {0.0, 0.0};
  plot.series.push_back(line);
  const std::string svg = plot.render(400, 300);
  EXPECT_EQ(count(svg, "<polygon class=\"band\""), 1u);
  const std::size_t polygon = svg.find("<polygon class=\"band\"");
  EXPECT_LT(polygon, svg.find("<polyline"));  // under the series
  const std::size_t at = svg.find("points=\"", polygon);
  const std::string pts = svg.substr(at + 8, svg.find('"', at + 8) - at - 8);
  EXPECT_EQ(count(pts, ","), 6u);  // three points along lo, three back along hi
  EXPECT_FALSE(has_nan(svg));
  EXPECT_NE(svg.find(">40<"), std::string::npos) << svg;  // the y axis reaches the top edge
  EXPECT_LT(svg.find(">line<"), svg.find(">the band<"));
}

}  // namespace
}  // namespace abbe::report
