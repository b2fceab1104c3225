#include "abbe/report/map_section.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "abbe/report/colour_map.hpp"

namespace abbe::report {
namespace {

// |d| of model m on one plane: "xy" at z index k, "xz" at y index k, "yz" at x index k.
ColourMap slice(const identify::WorkspaceMap& map, std::size_t m, const std::string& plane,
                std::size_t k) {
  const std::size_t nx = map.xs.size(), ny = map.ys.size();
  auto at = [&](std::size_t i, std::size_t j, std::size_t l) {
    return map.deviation_um[m][(l * ny + j) * nx + i].norm();
  };
  ColourMap c;
  const std::string model = model::to_string(map.models[m]);
  c.value_label = "|d|";
  c.value_unit = "µm";
  if (plane == "xy") {
    c.xs = map.xs, c.ys = map.ys;
    c.x = {"x", "mm", {}, {}}, c.y = {"y", "mm", {}, {}};
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) c.values.push_back(at(i, j, k));
    c.title = fmt::format("{}: |d| at z = {:g} mm", model, map.zs[k]);
  } else if (plane == "xz") {
    c.xs = map.xs, c.ys = map.zs;
    c.x = {"x", "mm", {}, {}}, c.y = {"z", "mm", {}, {}};
    for (std::size_t l = 0; l < map.zs.size(); ++l)
      for (std::size_t i = 0; i < nx; ++i) c.values.push_back(at(i, k, l));
    c.title = fmt::format("{}: |d| at y = {:g} mm", model, map.ys[k]);
  } else {
    c.xs = map.ys, c.ys = map.zs;
    c.x = {"y", "mm", {}, {}}, c.y = {"z", "mm", {}, {}};
    for (std::size_t l = 0; l < map.zs.size(); ++l)
      for (std::size_t j = 0; j < ny; ++j) c.values.push_back(at(k, j, l));
    c.title = fmt::format("{}: |d| at x = {:g} mm", model, map.xs[k]);
  }
  c.id = fmt::format("map-{}-{}{}", model, plane, k);
  return c;
}

}  // namespace

void render_map_report(HtmlPage& page, const identify::WorkspaceMap& map,
                       const std::string& machine_name) {
  page.add_fact("machine", machine_name);
  page.add_fact("grid", fmt::format("{} × {} × {} = {} points", map.xs.size(), map.ys.size(),
                                    map.zs.size(), map.points.size()));
  page.add_section("map-summary", "Volumetric error over the grid");
  Table t = make_table("map-table", "|d| over all grid points, per model",
                       {"model", "mean |d| (µm)", "rms |d| (µm)", "max |d| (µm)"});
  for (const auto& s : map.stats)
    t.rows.push_back({model::to_string(s.model), fmt::format("{:.3f}", s.mean_um),
                      fmt::format("{:.3f}", s.rms_um), fmt::format("{:.3f}", s.max_um)});
  page.add_table(t);
  if (map.has_comparison)
    page.add_paragraph(fmt::format(
        "htm against ae-arm: ae-arm's mean |d| is {:.3f} µm ({:.1f} %) {} than htm's; the two "
        "models' deviation vectors differ by {:.3f} µm on average (mean |d_htm − d_ae-arm|).",
        std::abs(map.mean_difference_um), std::abs(map.percent_smaller),
        map.mean_difference_um >= 0.0 ? "smaller" : "larger", map.mean_abs_vector_difference_um));
  if (map.out_of_range_lookups > 0)
    page.add_note(
        fmt::format("{} table lookups lay outside the measured range.", map.out_of_range_lookups));
  if (map.xs.empty() || map.ys.empty() || map.zs.empty()) return;

  // Models shown side by side: those without a second-order part (whose
  // first order another model already shows) when there are any, else all.
  std::vector<std::size_t> shown;
  for (std::size_t m = 0; m < map.models.size(); ++m)
    if (!model::descriptor(map.models[m]).second_order) shown.push_back(m);
  if (shown.empty())
    for (std::size_t m = 0; m < map.models.size(); ++m) shown.push_back(m);

  page.add_section("map-slices", "|d| on slices of the workspace");
  page.add_paragraph(
      "Each row is one slice; the maps of a row share the colour scale. Hover over a cell for "
      "its value.");
  std::vector<std::pair<std::string, std::size_t>> planes;
  const std::size_t nz = map.zs.size();
  for (std::size_t k : {std::size_t{0}, nz / 2, nz - 1})
    if (planes.empty() || planes.back().second != k) planes.emplace_back("xy", k);
  planes.emplace_back("xz", map.ys.size() / 2);
  planes.emplace_back("yz", map.xs.size() / 2);
  for (const auto& [plane, k] : planes) {
    std::vector<ColourMap> maps;
    double hi = 0.0;
    for (std::size_t m : shown) {
      maps.push_back(slice(map, m, plane, k));
      for (double v : maps.back().values) hi = std::max(hi, v);
    }
    // Height from the slice's aspect ratio (equal scale): plot area 360 px
    // wide and 160…480 px high. The cells reach half a step beyond the ends.
    auto extent = [](const std::vector<double>& v) {
      if (v.size() < 2) return 1.0;
      return (v.back() - v.front()) * static_cast<double>(v.size()) /
             static_cast<double>(v.size() - 1);
    };
    const double ratio = extent(maps.front().ys) / extent(maps.front().xs);
    const int height = 80 + static_cast<int>(std::clamp(360.0 * ratio, 160.0, 480.0));
    std::vector<std::string> svgs;
    for (auto& c : maps) {
      c.vmin = 0.0;
      c.vmax = hi;
      svgs.push_back(c.render(530, height));
    }
    page.add_figures(svgs);
  }
}

}  // namespace abbe::report
