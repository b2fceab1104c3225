#include "abbe/report/colour_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "abbe/report/plot_frame.hpp"
#include "abbe/report/svg.hpp"

namespace abbe::report {
namespace {

// Cell edges around the nodes: midpoints inside, half a spacing outside.
std::vector<double> cell_edges(const std::vector<double>& nodes) {
  std::vector<double> e(nodes.size() + 1);
  if (nodes.size() == 1) {
    e[0] = nodes[0] - 0.5;
    e[1] = nodes[0] + 0.5;
    return e;
  }
  for (std::size_t i = 1; i < nodes.size(); ++i) e[i] = 0.5 * (nodes[i - 1] + nodes[i]);
  e.front() = nodes.front() - 0.5 * (nodes[1] - nodes[0]);
  e.back() = nodes.back() + 0.5 * (nodes.back() - nodes[nodes.size() - 2]);
  return e;
}

}  // namespace

std::string ColourMap::render(int width, int height) const {
  if (xs.empty() || ys.empty() || values.size() != xs.size() * ys.size())
    throw std::invalid_argument(fmt::format("colour map {}: {} values for a {} × {} grid", id,
                                            values.size(), xs.size(), ys.size()));
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : values)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (vmin) lo = *vmin;
  if (vmax) hi = *vmax;
  widen_range(lo, hi);

  const std::vector<double> ex = cell_edges(xs), ey = cell_edges(ys);
  const double w = static_cast<double>(width), h = static_cast<double>(height);
  PlotFrame f;
  f.left = 74.0;
  f.right = w - 96.0;
  f.top = 34.0;
  f.bottom = h - 46.0;
  double x0 = ex.front(), x1 = ex.back(), y0 = ey.front(), y1 = ey.back();
  widen_range(x0, x1);
  widen_range(y0, y1);
  f.set_range(x0, x1, y0, y1, true);

  std::string o = f.open_svg(id, width, height, title);
  o += "<g class=\"cells\" stroke=\"none\">\n";
  const std::string unit = value_unit.empty() ? "" : " " + value_unit;
  for (std::size_t j = 0; j < ys.size(); ++j)
    for (std::size_t i = 0; i < xs.size(); ++i) {
      const double v = values[j * xs.size() + i];
      const double rx = f.px(ex[i]), ry = f.py(ey[j + 1]);
      const std::string text =
          std::isfinite(v)
              ? fmt::format("{} = {:g} {}, {} = {:g} {}: {} = {:.3f}{}", x.label, xs[i], x.unit,
                            y.label, ys[j], y.unit, value_label, v, unit)
              : fmt::format("{} = {:g} {}, {} = {:g} {}: no value", x.label, xs[i], x.unit, y.label,
                            ys[j], y.unit);
      // Cells overlap by half a pixel so that no background shows between them.
      o += fmt::format(
          "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\"><title>{}</title>"
          "</rect>\n",
          svg_coord(rx), svg_coord(ry), svg_coord(f.px(ex[i + 1]) - rx + 0.5),
          svg_coord(f.py(ey[j]) - ry + 0.5),
          viridis(std::isfinite(v) ? (v - lo) / (hi - lo) : std::nan("")), escape_xml(text));
    }
  o += "</g>\n";
  o += f.axes(x, y, false);

  // Scale bar: the legend of the colours.
  const double bx = f.right + 18.0, bw = 16.0, bt = f.top, bb = f.bottom;
  constexpr int kSteps = 64;
  o += "<g class=\"scale-bar\">\n";
  for (int k = 0; k < kSteps; ++k) {
    const double t0 = static_cast<double>(k) / kSteps, t1 = static_cast<double>(k + 1) / kSteps;
    const double ya = bb - t1 * (bb - bt), yb = bb - t0 * (bb - bt);
    o += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\"/>",
                     svg_coord(bx), svg_coord(ya), svg_coord(bw), svg_coord(yb - ya + 0.5),
                     viridis(0.5 * (t0 + t1)));
  }
  o += fmt::format(
      "\n<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#333\"/>\n",
      svg_coord(bx), svg_coord(bt), svg_coord(bw), svg_coord(bb - bt));
  const Ticks t = nice_ticks(lo, hi, 6);
  for (double v : t.values) {
    const double yy = bb - (v - lo) / (hi - lo) * (bb - bt);
    o += fmt::format(
        "<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"#333\"/>"
        "<text x=\"{3}\" y=\"{4}\" fill=\"#333\">{5}</text>\n",
        svg_coord(bx + bw), svg_coord(yy), svg_coord(bx + bw + 4.0), svg_coord(bx + bw + 6.0),
        svg_coord(yy + 4.0), format_tick(v, t.step));
  }
  const std::string bar_title =
      value_unit.empty() ? value_label : value_label + " (" + value_unit + ")";
  o += fmt::format(
      "<text class=\"scale-title\" x=\"0\" y=\"0\" text-anchor=\"middle\" "
      "transform=\"translate({},{}) rotate(-90)\">{}</text>\n</g>\n</svg>\n",
      svg_coord(w - 10.0), svg_coord(0.5 * (bt + bb)), escape_xml(bar_title));
  return o;
}

}  // namespace abbe::report
