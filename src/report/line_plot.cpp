#include "abbe/report/line_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "abbe/report/plot_frame.hpp"
#include "abbe/report/svg.hpp"

namespace abbe::report {
namespace {

// Legend items left to right, wrapped into rows of at most `width` px.
struct LegendLayout {
  std::vector<std::pair<double, int>> pos;  // x offset, row
  int rows = 0;
};

double legend_item_width(const std::string& name) {
  return 44.0 + 7.4 * static_cast<double>(name.size());
}

LegendLayout layout_legend(const std::vector<std::string>& names, double width) {
  LegendLayout l;
  double x = 0.0;
  int row = 0;
  for (const auto& name : names) {
    if (name.empty()) {  // not in the legend
      l.pos.emplace_back(x, row);
      continue;
    }
    const double w = legend_item_width(name);
    if (x > 0.0 && x + w > width) {
      x = 0.0;
      ++row;
    }
    l.pos.emplace_back(x, row);
    x += w;
  }
  l.rows = names.empty() ? 0 : row + 1;
  return l;
}

std::string stroke_of(const Series& s, std::size_t i) {
  return s.colour.empty() ? series_colour(i) : s.colour;
}

constexpr double kBandOpacity = 0.2;

// The band as one polygon: along lo, back along hi (points where either
// edge is not finite are left out).
std::string band_polygon(const Band& b, const PlotFrame& f) {
  const std::size_t n = std::min({b.x.size(), b.lo.size(), b.hi.size()});
  std::vector<std::size_t> ok;
  for (std::size_t i = 0; i < n; ++i)
    if (std::isfinite(b.x[i]) && std::isfinite(b.lo[i]) && std::isfinite(b.hi[i])) ok.push_back(i);
  if (ok.empty()) return {};
  std::string pts;
  auto add = [&](double xv, double yv) {
    if (!pts.empty()) pts += ' ';
    pts += svg_coord(f.px(xv));
    pts += ',';
    pts += svg_coord(f.py(yv));
  };
  for (std::size_t i : ok) add(b.x[i], b.lo[i]);
  for (auto it = ok.rbegin(); it != ok.rend(); ++it) add(b.x[*it], b.hi[*it]);
  return fmt::format(
      "<polygon class=\"band\" fill=\"{}\" fill-opacity=\"{}\" stroke=\"none\" "
      "points=\"{}\"/>\n",
      b.colour, kBandOpacity, pts);
}

}  // namespace

std::string LinePlot::render(int width, int height) const {
  // Data range over the finite points.
  double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo, ylo = xlo, yhi = -xlo;
  auto extend = [&](double xv, double yv) {
    if (!std::isfinite(xv) || !std::isfinite(yv)) return;
    xlo = std::min(xlo, xv);
    xhi = std::max(xhi, xv);
    ylo = std::min(ylo, yv);
    yhi = std::max(yhi, yv);
  };
  for (const auto& s : series)
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) extend(s.x[i], s.y[i]);
  for (const auto& b : bands)
    for (std::size_t i = 0; i < std::min({b.x.size(), b.lo.size(), b.hi.size()}); ++i) {
      extend(b.x[i], b.lo[i]);
      extend(b.x[i], b.hi[i]);
    }
  if (!(xlo <= xhi)) xlo = 0.0, xhi = 1.0;
  if (!(ylo <= yhi)) ylo = 0.0, yhi = 1.0;
  widen_range(xlo, xhi);
  widen_range(ylo, yhi);
  const double px_ = 0.04 * (xhi - xlo), py_ = 0.06 * (yhi - ylo);
  xlo -= px_, xhi += px_, ylo -= py_, yhi += py_;
  if (x.lo) xlo = *x.lo;
  if (x.hi) xhi = *x.hi;
  if (y.lo) ylo = *y.lo;
  if (y.hi) yhi = *y.hi;
  widen_range(xlo, xhi);
  widen_range(ylo, yhi);

  const double w = static_cast<double>(width), h = static_cast<double>(height);
  std::vector<std::string> names;
  for (const auto& s : series) names.push_back(s.name);
  for (const auto& b : bands) names.push_back(b.name);
  const LegendLayout legend = layout_legend(names, w - 90.0);
  PlotFrame f;
  f.left = 74.0;
  f.right = w - 18.0;
  f.top = 34.0 + 18.0 * legend.rows + 8.0;
  f.bottom = h - 46.0;
  f.set_range(xlo, xhi, ylo, yhi, equal_scale);

  std::string o;
  o += f.open_svg(id, width, height, title);
  o += f.axes(x, y);

  // Series, clipped to the plot area.
  o += fmt::format("<g clip-path=\"url(#{}-clip)\">\n", escape_xml(id));
  for (const Band& b : bands) o += band_polygon(b, f);
  for (std::size_t si = 0; si < series.size(); ++si) {
    const Series& s = series[si];
    const std::string colour = stroke_of(s, si);
    const std::size_t n = std::min(s.x.size(), s.y.size());
    if (s.style == SeriesStyle::markers) {
      o += fmt::format("<g fill=\"{}\">", colour);
      for (std::size_t i = 0; i < n; ++i)
        if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]))
          o += fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"{}\"/>", svg_coord(f.px(s.x[i])),
                           svg_coord(f.py(s.y[i])), svg_coord(s.width));
      o += "</g>\n";
      continue;
    }
    const std::string dash = s.style == SeriesStyle::dashed ? " stroke-dasharray=\"6,4\"" : "";
    std::string pts;
    auto flush = [&] {
      if (!pts.empty())
        o += fmt::format(
            "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"{}\"{} "
            "stroke-linejoin=\"round\" points=\"{}\"/>\n",
            colour, svg_coord(s.width), dash, pts);
      pts.clear();
    };
    for (std::size_t i = 0; i < n; ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
        flush();
        continue;
      }
      if (!pts.empty()) pts += ' ';
      pts += svg_coord(f.px(s.x[i]));
      pts += ',';
      pts += svg_coord(f.py(s.y[i]));
    }
    flush();
  }
  o += "</g>\n";

  // Hover targets: transparent circles with a <title>, spread evenly.
  std::size_t with_hover = 0;
  for (const auto& s : series)
    if (!s.hover.empty()) with_hover += std::min(s.hover.size(), s.x.size());
  if (with_hover > 0 && max_hover_targets > 0) {
    const std::size_t stride = (with_hover + max_hover_targets - 1) / max_hover_targets;
    o += "<g class=\"hover\">\n";
    for (std::size_t si = 0; si < series.size(); ++si) {
      const Series& s = series[si];
      const std::size_t n = std::min({s.hover.size(), s.x.size(), s.y.size()});
      for (std::size_t i = 0; i < n; i += stride) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
        o += fmt::format(
            "<circle cx=\"{}\" cy=\"{}\" r=\"4\" fill=\"{}\" fill-opacity=\"0\"><title>{}</title>"
            "</circle>\n",
            svg_coord(f.px(s.x[i])), svg_coord(f.py(s.y[i])), stroke_of(s, si),
            escape_xml(s.hover[i]));
      }
    }
    o += "</g>\n";
  }

  // Direction key (projected axes) in the upper left corner of the area.
  if (!directions.empty()) {
    const double ox = f.left + 36.0, oy = f.top + 40.0;
    o += "<g class=\"directions\" stroke=\"#444\" fill=\"#444\">\n";
    for (const auto& d : directions) {
      // Screen direction: data dy is up, so it is subtracted.
      double sx = d.dx * f.sx, sy = -d.dy * f.sy;
      const double len = std::hypot(sx, sy);
      if (!(len > 0.0) || !std::isfinite(len)) continue;
      sx *= 26.0 / len;
      sy *= 26.0 / len;
      o += fmt::format(
          "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke-width=\"1.5\"/>"
          "<circle cx=\"{}\" cy=\"{}\" r=\"2.5\"/>"
          "<text x=\"{}\" y=\"{}\" stroke=\"none\" text-anchor=\"middle\" "
          "dominant-baseline=\"middle\">{}</text>\n",
          svg_coord(ox), svg_coord(oy), svg_coord(ox + sx), svg_coord(oy + sy), svg_coord(ox + sx),
          svg_coord(oy + sy), svg_coord(ox + 1.45 * sx), svg_coord(oy + 1.45 * sy),
          escape_xml(d.label));
    }
    o += "</g>\n";
  }

  // Legend above the plot area.
  o += "<g class=\"legend\">\n";
  for (std::size_t si = 0; si < series.size(); ++si) {
    const Series& s = series[si];
    if (s.name.empty()) continue;
    const double lx = f.left + legend.pos[si].first;
    const double ly = 36.0 + 18.0 * legend.pos[si].second;
    const std::string colour = stroke_of(s, si);
    if (s.style == SeriesStyle::markers)
      o += fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"4\" fill=\"{}\"/>", svg_coord(lx + 11.0),
                       svg_coord(ly), colour);
    else
      o += fmt::format(
          "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"{}\" stroke-width=\"2.5\"{}/>",
          svg_coord(lx), svg_coord(ly), svg_coord(lx + 24.0), svg_coord(ly), colour,
          s.style == SeriesStyle::dashed ? " stroke-dasharray=\"6,4\"" : "");
    o += fmt::format("<text x=\"{}\" y=\"{}\" dominant-baseline=\"middle\">{}</text>\n",
                     svg_coord(lx + 29.0), svg_coord(ly + 0.5), escape_xml(s.name));
  }
  for (std::size_t bi = 0; bi < bands.size(); ++bi) {
    const Band& b = bands[bi];
    if (b.name.empty()) continue;
    const auto& pos = legend.pos[series.size() + bi];
    const double lx = f.left + pos.first, ly = 36.0 + 18.0 * pos.second;
    o += fmt::format(
        "<rect x=\"{}\" y=\"{}\" width=\"24\" height=\"10\" fill=\"{}\" fill-opacity=\"{}\"/>"
        "<text x=\"{}\" y=\"{}\" dominant-baseline=\"middle\">{}</text>\n",
        svg_coord(lx), svg_coord(ly - 5.0), b.colour, kBandOpacity, svg_coord(lx + 29.0),
        svg_coord(ly + 0.5), escape_xml(b.name));
  }
  o += "</g>\n</svg>\n";
  return o;
}

}  // namespace abbe::report
