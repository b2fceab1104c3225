#include "abbe/report/plot_frame.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "abbe/report/svg.hpp"

namespace abbe::report {

std::string axis_title(const AxisSpec& a) {
  return a.unit.empty() ? a.label : a.label + " (" + a.unit + ")";
}

void PlotFrame::set_range(double x0, double x1, double y0, double y1, bool equal_scale) {
  xlo = x0, xhi = x1, ylo = y0, yhi = y1;
  const double w = std::max(right - left, 1.0), h = std::max(bottom - top, 1.0);
  sx = w / (xhi - xlo);
  sy = h / (yhi - ylo);
  if (equal_scale) {
    const double s = std::min(sx, sy);
    const double xc = 0.5 * (xlo + xhi), yc = 0.5 * (ylo + yhi);
    xlo = xc - 0.5 * w / s, xhi = xc + 0.5 * w / s;
    ylo = yc - 0.5 * h / s, yhi = yc + 0.5 * h / s;
    sx = sy = s;
  }
}

std::string PlotFrame::open_svg(const std::string& plot_id, int width, int height,
                                const std::string& title) {
  id = plot_id;
  return fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" id=\"{0}\" class=\"plot\" "
      "width=\"{1}\" height=\"{2}\" viewBox=\"0 0 {1} {2}\" font-family=\"DejaVu Sans, Arial, "
      "sans-serif\" font-size=\"12\">\n"
      "<rect x=\"0\" y=\"0\" width=\"{1}\" height=\"{2}\" fill=\"#ffffff\"/>\n"
      "<text class=\"plot-title\" x=\"{3}\" y=\"20\" text-anchor=\"middle\" font-size=\"14\" "
      "font-weight=\"bold\">{4}</text>\n",
      escape_xml(plot_id), width, height, svg_coord(0.5 * width), escape_xml(title));
}

std::string PlotFrame::axes(const AxisSpec& x, const AxisSpec& y, bool grid) const {
  std::string o;
  const int xt = std::max(3, static_cast<int>((right - left) / 90.0));
  const int yt = std::max(4, static_cast<int>((bottom - top) / 50.0));
  const Ticks tx = nice_ticks(xlo, xhi, xt), ty = nice_ticks(ylo, yhi, yt);
  o += "<g class=\"grid\" stroke=\"#e4e4e4\" stroke-width=\"1\">\n";
  for (double v : grid ? tx.values : std::vector<double>{})
    o += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\"/>", svg_coord(px(v)),
                     svg_coord(top), svg_coord(bottom));
  for (double v : grid ? ty.values : std::vector<double>{})
    o += fmt::format("<line x1=\"{1}\" y1=\"{0}\" x2=\"{2}\" y2=\"{0}\"/>", svg_coord(py(v)),
                     svg_coord(left), svg_coord(right));
  o += "\n</g>\n<g class=\"axes\" stroke=\"#333\" stroke-width=\"1\">\n";
  for (double v : tx.values)
    o += fmt::format(
        "<line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{2}\"/><text x=\"{0}\" y=\"{3}\" "
        "stroke=\"none\" fill=\"#333\" text-anchor=\"middle\">{4}</text>\n",
        svg_coord(px(v)), svg_coord(bottom), svg_coord(bottom + 5.0), svg_coord(bottom + 18.0),
        format_tick(v, tx.step));
  for (double v : ty.values)
    o += fmt::format(
        "<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\"/><text x=\"{3}\" y=\"{4}\" "
        "stroke=\"none\" fill=\"#333\" text-anchor=\"end\">{5}</text>\n",
        svg_coord(left - 5.0), svg_coord(py(v)), svg_coord(left), svg_coord(left - 8.0),
        svg_coord(py(v) + 4.0), format_tick(v, ty.step));
  o += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\"/>\n</g>\n",
                   svg_coord(left), svg_coord(top), svg_coord(right - left),
                   svg_coord(bottom - top));
  o += fmt::format(
      "<text class=\"axis-label\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n",
      svg_coord(0.5 * (left + right)), svg_coord(bottom + 36.0), escape_xml(axis_title(x)));
  o += fmt::format(
      "<text class=\"axis-label\" x=\"0\" y=\"0\" text-anchor=\"middle\" "
      "transform=\"translate({},{}) rotate(-90)\">{}</text>\n",
      svg_coord(16.0), svg_coord(0.5 * (top + bottom)), escape_xml(axis_title(y)));
  o += fmt::format(
      "<defs><clipPath id=\"{}-clip\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>"
      "</clipPath></defs>\n",
      escape_xml(id), svg_coord(left), svg_coord(top), svg_coord(right - left),
      svg_coord(bottom - top));
  return o;
}

}  // namespace abbe::report
