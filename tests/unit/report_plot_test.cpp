// LinePlot, ColourMap and HtmlPage: what every plot must contain (title,
// axes with units, legend or scale bar, hover titles) and what it must not
// (NaN, unescaped text).
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>

#include "abbe/report/colour_map.hpp"
#include "abbe/report/html_page.hpp"
#include "abbe/report/line_plot.hpp"

namespace abbe::report {
namespace {

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (auto p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

bool has_non_finite(const std::string& svg) {
  return std::regex_search(svg, std::regex("\\bnan\\b|\\binf\\b", std::regex::icase));
}

LinePlot sample_plot() {
  LinePlot p;
  p.id = "dev";
  p.title = "Deviation <along> the path";
  p.x = {"path length", "mm", {}, {}};
  p.y = {"deviation", "µm", {}, {}};
  Series a;
  a.name = "dx";
  a.x = {0.0, 10.0, 20.0, 30.0};
  a.y = {1.0, -2.0, 3.0, 0.5};
  a.hover = {"line 1: G1 X<5", "line 2", "line 3", "line 4"};
  Series b;
  b.name = "dy & dz";
  b.style = SeriesStyle::markers;
  b.x = {0.0, 30.0};
  b.y = {0.0, 1.0};
  p.series = {a, b};
  return p;
}

TEST(ReportPlot, LinePlotHasTitleAxesWithUnitsLegendAndHover) {
  const std::string svg = sample_plot().render(600, 300);
  EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
  EXPECT_NE(svg.find("id=\"dev\""), std::string::npos);
  EXPECT_NE(svg.find(">Deviation &lt;along&gt; the path</text>"), std::string::npos);
  EXPECT_NE(svg.find(">path length (mm)</text>"), std::string::npos);
  EXPECT_NE(svg.find(">deviation (µm)</text>"), std::string::npos);
  EXPECT_NE(svg.find("class=\"legend\""), std::string::npos);
  EXPECT_NE(svg.find(">dx</text>"), std::string::npos);
  EXPECT_NE(svg.find(">dy &amp; dz</text>"), std::string::npos);
  EXPECT_EQ(count(svg, "<title>"), 4u);
  EXPECT_NE(svg.find("<title>line 1: G1 X&lt;5</title>"), std::string::npos);
  // x ticks 0, 10, 20, 30 (step 10 on a 540 px wide area) are labelled.
  for (const char* t : {">0</text>", ">10</text>", ">20</text>", ">30</text>"})
    EXPECT_NE(svg.find(t), std::string::npos) << t;
  EXPECT_EQ(count(svg, "<polyline"), 1u);
  EXPECT_EQ(count(svg, "<svg"), 1u);
  EXPECT_EQ(count(svg, "</svg>"), 1u);
  EXPECT_FALSE(has_non_finite(svg));
}

TEST(ReportPlot, PointsMapInsideThePlotAreaWithYUp) {
  LinePlot p;
  p.id = "p";
  p.title = "t";
  p.x = {"x", "mm", 0.0, 100.0};
  p.y = {"y", "mm", 0.0, 100.0};
  Series s;
  s.name = "s";
  s.x = {0.0, 100.0};
  s.y = {0.0, 100.0};
  p.series = {s};
  const std::string svg = p.render(400, 300);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(
      svg, m, std::regex("points=\"([-0-9.]+),([-0-9.]+) ([-0-9.]+),([-0-9.]+)\"")));
  const double x0 = std::stod(m[1]), y0 = std::stod(m[2]), x1 = std::stod(m[3]),
               y1 = std::stod(m[4]);
  EXPECT_LT(x0, x1);
  EXPECT_GT(y0, y1);  // larger y is higher up on the screen
  for (double v : {x0, x1}) EXPECT_TRUE(v > 0 && v < 400) << v;
  for (double v : {y0, y1}) EXPECT_TRUE(v > 0 && v < 300) << v;
}

TEST(ReportPlot, NonFinitePointsSplitTheLineAndNeverReachTheOutput) {
  LinePlot p = sample_plot();
  p.series[0].y[1] = std::nan("");
  p.series[0].x[2] = std::numeric_limits<double>::infinity();
  const std::string svg = p.render(600, 300);
  EXPECT_FALSE(has_non_finite(svg));
  EXPECT_EQ(count(svg, "<polyline"), 2u);  // 0 | (nan) | (inf) | 30
  LinePlot all_nan;
  all_nan.id = "n";
  all_nan.title = "no finite data";
  Series s;
  s.name = "no finite point";
  s.x = {std::nan(""), std::nan("")};
  s.y = {1.0, std::nan("")};
  all_nan.series = {s};
  EXPECT_FALSE(has_non_finite(all_nan.render(300, 200)));
}

TEST(ReportPlot, EqualScaleGivesTheSamePixelsPerMillimetre) {
  LinePlot p;
  p.id = "xy";
  p.title = "XY";
  p.equal_scale = true;
  Series s;
  s.name = "square";
  s.x = {0.0, 100.0, 100.0, 0.0, 0.0};
  s.y = {0.0, 0.0, 100.0, 100.0, 0.0};
  p.series = {s};
  const std::string svg = p.render(800, 300);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(
      svg, m,
      std::regex("points=\"([-0-9.]+),([-0-9.]+) ([-0-9.]+),([-0-9.]+) ([-0-9.]+),([-0-9.]+)")));
  const double w = std::stod(m[3]) - std::stod(m[1]);
  const double h = std::stod(m[4]) - std::stod(m[6]);
  EXPECT_NEAR(w, h, 0.02);
  EXPECT_GT(w, 50.0);
}

TEST(ReportPlot, ColourMapHasScaleBarWithTicksAndHoverPerCell) {
  ColourMap c;
  c.id = "map-htm";
  c.title = "htm: |d| at z = -300 mm";
  c.x = {"x", "mm", {}, {}};
  c.y = {"y", "mm", {}, {}};
  c.value_label = "|d|";
  c.value_unit = "µm";
  c.xs = {-100.0, -50.0, 0.0};
  c.ys = {-20.0, 0.0};
  c.values = {0.0, 1.0, 2.0, 3.0, 4.0, std::nan("")};
  c.vmin = 0.0;
  c.vmax = 5.0;
  const std::string svg = c.render(500, 400);
  EXPECT_NE(svg.find("class=\"scale-bar\""), std::string::npos);
  EXPECT_NE(svg.find(">|d| (µm)</text>"), std::string::npos);
  EXPECT_NE(svg.find(">x (mm)</text>"), std::string::npos);
  EXPECT_NE(svg.find(">y (mm)</text>"), std::string::npos);
  // Scale bar ticks 0…5 (step 1): each label appears.
  for (const char* t : {">0</text>", ">1</text>", ">5</text>"})
    EXPECT_NE(svg.find(t), std::string::npos) << t;
  // One hover title per cell; the value at (x=0, y=-20) is 2.
  EXPECT_EQ(count(svg, "<title>"), 6u);
  EXPECT_NE(svg.find("<title>x = 0 mm, y = -20 mm: |d| = 2.000 µm</title>"), std::string::npos);
  EXPECT_NE(svg.find("no value</title>"), std::string::npos);
  // The lowest value gets the bottom colour of the scale, the top one the top.
  EXPECT_NE(svg.find("fill=\"#440154\"><title>x = -100 mm, y = -20 mm"), std::string::npos);
  EXPECT_FALSE(has_non_finite(svg));

  c.values.pop_back();
  EXPECT_THROW(c.render(500, 400), std::invalid_argument);
}

TEST(ReportPlot, HtmlPageIsSelfContained) {
  HtmlPage page("Report <1>");
  page.add_fact("program", "a&b.ngc");
  page.add_section("summary", "Summary");
  page.add_table({"caption", {"model", "max |d| (µm)"}, {{"htm", "1.5"}}, "t1"});
  page.add_figures({sample_plot().render(300, 200)});
  const std::string html = page.render();
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("<meta charset=\"utf-8\">"), std::string::npos);
  EXPECT_NE(html.find("<title>Report &lt;1&gt;</title>"), std::string::npos);
  EXPECT_NE(html.find("a&amp;b.ngc"), std::string::npos);
  EXPECT_NE(html.find("<h2 id=\"summary\">Summary</h2>"), std::string::npos);
  EXPECT_NE(html.find("<td>htm</td><td>1.5</td>"), std::string::npos);
  EXPECT_NE(html.find("id=\"dev\""), std::string::npos);
  // Nothing is fetched: no external scripts, styles, images or fonts.
  EXPECT_EQ(html.find("src="), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(count(html, "http://"), count(html, "http://www.w3.org/2000/svg"));
  EXPECT_EQ(html.find("https://"), std::string::npos);
}

}  // namespace
}  // namespace abbe::report
