#pragma once
// LinePlot: an x–y chart as one SVG element — title, legend, axes with ticks
// and units, any number of series drawn as polylines or markers, per-point
// hover text (SVG <title>, shown as a tooltip by every browser), optional
// equal scale on both axes (for toolpaths in a plane) and an optional key of
// projected direction arrows (for 3-D projections).
#include <optional>
#include <string>
#include <vector>

namespace abbe::report {

struct AxisSpec {
  std::string label;             // e.g. "x"
  std::string unit;              // e.g. "mm"; shown as "label (unit)"
  std::optional<double> lo, hi;  // fixed range; default: the data's (padded)
};

enum class SeriesStyle { line, dashed, markers };

struct Series {
  std::string name;    // legend text; empty: not in the legend
  std::string colour;  // "#rrggbb"; empty: series_colour(index)
  SeriesStyle style = SeriesStyle::line;
  double width = 1.5;  // line width or marker radius, px
  std::vector<double> x, y;
  // Per-point hover text (same length as x, or empty). Points with text get
  // an invisible hover target; at most `max_hover_targets` per plot, spread
  // evenly along the series.
  std::vector<std::string> hover;
};

// The area between two curves, filled (translucent, no outline) under the
// series: e.g. a value ± its expanded uncertainty.
struct Band {
  std::string name;    // legend text; empty: not in the legend
  std::string colour;  // "#rrggbb"
  std::vector<double> x, lo, hi;
};

// A direction drawn as an arrow in the plot's corner, e.g. the X, Y and Z
// axes of a 3-D projection (dx, dy in data units, only the direction counts).
struct DirectionKey {
  std::string label;
  double dx = 0.0, dy = 0.0;
};

struct LinePlot {
  std::string id;  // id attribute of the <svg>, unique in the page
  std::string title;
  AxisSpec x, y;
  std::vector<Series> series;
  std::vector<Band> bands;  // drawn first, in the legend after the series
  bool equal_scale = false;  // 1 data unit = the same length on both axes
  std::vector<DirectionKey> directions;
  std::size_t max_hover_targets = 2000;

  // The <svg> element (width × height px). Non-finite points are dropped
  // (a polyline is split there); the output never contains "nan" or "inf".
  std::string render(int width, int height) const;
};

}  // namespace abbe::report
