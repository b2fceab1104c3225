#pragma once
// PlotFrame: the mapping from data to pixel coordinates of one plot area
// and the parts every plot shares — the <svg> opening, the title, grid
// lines, ticks with labels, axis labels with units and the clip path of the
// area (id "<plot id>-clip").
#include <string>

#include "abbe/report/line_plot.hpp"

namespace abbe::report {

struct PlotFrame {
  double left = 0.0, right = 1.0, top = 0.0, bottom = 1.0;  // plot area, px
  double xlo = 0.0, xhi = 1.0, ylo = 0.0, yhi = 1.0;        // data range
  double sx = 1.0, sy = 1.0;                                // px per data unit
  std::string id;

  // Sets the data range (already widened); with `equal_scale` the range of
  // one axis grows about its centre so that sx == sy.
  void set_range(double x0, double x1, double y0, double y1, bool equal_scale);
  double px(double x) const { return left + (x - xlo) * sx; }
  double py(double y) const { return bottom - (y - ylo) * sy; }

  // "<svg …>" with white background and the title text.
  std::string open_svg(const std::string& plot_id, int width, int height, const std::string& title);
  // Grid, ticks, tick labels, axis labels "label (unit)", frame, clip path.
  // `grid` = false leaves out the grid lines (colour maps).
  std::string axes(const AxisSpec& x, const AxisSpec& y, bool grid = true) const;
};

// "label (unit)", or the label alone without a unit.
std::string axis_title(const AxisSpec& a);

}  // namespace abbe::report
