// The SVG building blocks: escaping, coordinates, ticks, colour scale.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "abbe/report/svg.hpp"

namespace abbe::report {
namespace {

TEST(ReportSvg, EscapesMarkupAndDropsControlCharacters) {
  EXPECT_EQ(escape_xml("a<b & c>\"d\" 'e'"), "a&lt;b &amp; c&gt;&quot;d&quot; &#39;e&#39;");
  EXPECT_EQ(escape_xml(std::string("x\x01y\tz\n", 7)), "xy\tz\n");
  EXPECT_EQ(escape_xml("µm (G1 X-350)"), "µm (G1 X-350)");  // UTF-8 kept
  EXPECT_EQ(escape_xml("</script><svg onload=x>"), "&lt;/script&gt;&lt;svg onload=x&gt;");
}

TEST(ReportSvg, CoordinatesAreShortAndAlwaysFinite) {
  EXPECT_EQ(svg_coord(12.5), "12.5");
  EXPECT_EQ(svg_coord(3.0), "3");
  EXPECT_EQ(svg_coord(-0.001), "0");
  EXPECT_EQ(svg_coord(-7.126), "-7.13");
  EXPECT_EQ(svg_coord(std::nan("")), "0");
  EXPECT_EQ(svg_coord(std::numeric_limits<double>::infinity()), "0");
}

TEST(ReportSvg, TicksAreNiceStepsInsideTheRange) {
  const Ticks t = nice_ticks(-990.0, 0.0, 6);
  EXPECT_DOUBLE_EQ(t.step, 200.0);
  ASSERT_EQ(t.values.size(), 5u);
  EXPECT_DOUBLE_EQ(t.values.front(), -800.0);
  EXPECT_DOUBLE_EQ(t.values.back(), 0.0);
  for (double v : t.values) EXPECT_TRUE(v >= -990.0 && v <= 0.0);

  const Ticks small = nice_ticks(0.013, 0.087, 4);
  EXPECT_DOUBLE_EQ(small.step, 0.02);
  EXPECT_NEAR(small.values.front(), 0.02, 1e-12);
  EXPECT_EQ(format_tick(small.values.front(), small.step), "0.02");
  EXPECT_EQ(format_tick(-200.0, 200.0), "-200");
  EXPECT_EQ(format_tick(-1e-17, 0.5), "0");

  // Every tick step is 1, 2 or 5 times a power of ten, for many ranges.
  for (double hi : {0.7, 3.3, 17.0, 123.0, 4567.0, 1e-4}) {
    const Ticks r = nice_ticks(0.0, hi, 5);
    const double m = r.step / std::pow(10.0, std::floor(std::log10(r.step) + 1e-12));
    EXPECT_TRUE(std::abs(m - 1) < 1e-9 || std::abs(m - 2) < 1e-9 || std::abs(m - 5) < 1e-9)
        << hi << ": " << r.step;
    EXPECT_GE(r.values.size(), 2u) << hi;
    EXPECT_LE(r.values.size(), 11u) << hi;
  }
}

TEST(ReportSvg, DegenerateRangesAreWidened) {
  double lo = 5.0, hi = 5.0;
  widen_range(lo, hi);
  EXPECT_LT(lo, 5.0);
  EXPECT_GT(hi, 5.0);
  lo = std::nan(""), hi = 1.0;
  widen_range(lo, hi);
  EXPECT_EQ(lo, 0.0);
  EXPECT_EQ(hi, 1.0);
  const Ticks t = nice_ticks(0.0, 0.0);
  EXPECT_FALSE(t.values.empty());
}

TEST(ReportSvg, ViridisRunsFromDarkBlueToYellow) {
  EXPECT_EQ(viridis(0.0), "#440154");
  EXPECT_EQ(viridis(1.0), "#fde725");
  EXPECT_EQ(viridis(-3.0), viridis(0.0));
  EXPECT_EQ(viridis(7.0), viridis(1.0));
  EXPECT_EQ(viridis(std::nan("")), "#999999");
  EXPECT_NE(viridis(0.5), viridis(0.6));
  EXPECT_NE(series_colour(0), series_colour(1));
}

}  // namespace
}  // namespace abbe::report
