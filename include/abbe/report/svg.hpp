#pragma once
// Small building blocks of the SVG plots: XML escaping, numbers that are
// always finite in the output, "nice" axis ticks and the colour scales.
// Plain SVG 1.1 only (no CSS variables, no foreignObject), so a page looks
// the same in every browser.
#include <string>
#include <string_view>
#include <vector>

namespace abbe::report {

// Escapes &, <, >, " and ' for text and attribute values; drops control
// characters other than tab/newline (not allowed in XML 1.0).
std::string escape_xml(std::string_view text);

// A coordinate for an SVG attribute: fixed with 2 decimals, "-0" as "0";
// a non-finite value is written as 0 (callers drop such points first).
std::string svg_coord(double v);

// Axis ticks: values k·step within [lo, hi], step = 1, 2 or 5 × 10ⁿ chosen so
// that there are about `target` of them. A degenerate or non-finite range is
// widened first (see widen_range).
struct Ticks {
  double step = 1.0;
  std::vector<double> values;
};
Ticks nice_ticks(double lo, double hi, int target = 6);

// Makes [lo, hi] a usable axis range: non-finite → [0, 1]; lo == hi → ±1
// (or ±10 % of |lo|); swapped ends are ordered.
void widen_range(double& lo, double& hi);

// A tick label with as many decimals as the step needs ("0.25", "100", "-5").
std::string format_tick(double v, double step);

// Colour of a value t ∈ [0, 1] on the perceptually uniform viridis scale
// (dark blue → green → yellow), "#rrggbb"; t is clamped, NaN gives grey.
std::string viridis(double t);

// Distinct line colours for series i = 0, 1, … (colour-blind safe: Okabe–Ito
// without green, so no red/green pair)
std::string series_colour(std::size_t i);

}  // namespace abbe::report
