#pragma once
// ColourMap: a scalar field on a rectangular grid (e.g. |d| on a slice of
// the workspace) as one SVG element — a cell per grid node coloured on the
// viridis scale, axes with units, a title, a scale bar with ticks as the
// legend, and the value of each cell on hover.
#include <optional>
#include <string>
#include <vector>

#include "abbe/report/line_plot.hpp"

namespace abbe::report {

struct ColourMap {
  std::string id;
  std::string title;
  AxisSpec x, y;            // the grid axes (the range is the grid's)
  std::string value_label;  // e.g. "|d|"
  std::string value_unit;   // e.g. "µm"
  std::vector<double> xs;   // grid node positions, increasing
  std::vector<double> ys;
  std::vector<double> values;        // ys.size() × xs.size(), x fastest; NaN = no value (grey)
  std::optional<double> vmin, vmax;  // colour range (share it between maps to compare)

  // The <svg> element; throws std::invalid_argument when values.size() does
  // not match the grid.
  std::string render(int width, int height) const;
};

}  // namespace abbe::report
