#include "abbe/report/predict_section.hpp"

#include <fmt/format.h>

#include <cmath>

#include "abbe/report/line_plot.hpp"
#include "abbe/report/svg.hpp"

namespace abbe::report {
namespace {

const char* model_colour(model::ModelKind k) { return model::descriptor(k).colour.c_str(); }

std::string model_name(model::ModelKind k) { return model::to_string(k); }

std::string hover_text(const PredictedPath& r, std::size_t model, std::size_t i) {
  const Eigen::Vector3d& d = r.deviation_um[model][i];
  auto src = r.source.find(r.line[i]);
  return fmt::format(
      "line {}: {}\n{}: P = ({:.3f}, {:.3f}, {:.3f}) mm, s = {:.1f} mm\nd = ({:.3f}, {:.3f}, "
      "{:.3f}) µm, |d| = {:.3f} µm",
      r.line[i], src == r.source.end() ? "" : src->second, model_name(r.models[model]),
      r.nominal[i].x(), r.nominal[i].y(), r.nominal[i].z(), r.path_length[i], d.x(), d.y(), d.z(),
      d.norm());
}

// Nominal and exaggerated predicted toolpaths in one view.
LinePlot toolpath_plot(const PredictedPath& r, double k, const std::string& id,
                       const std::string& title, int u, int v, bool iso) {
  LinePlot plot;
  plot.id = id;
  plot.title = title;
  plot.equal_scale = true;
  const char* names = "xyz";
  if (iso) {
    plot.x = {"isometric horizontal", "mm", {}, {}};
    plot.y = {"isometric vertical", "mm", {}, {}};
    for (int a = 0; a < 3; ++a) {
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[a] = 1.0;
      const Eigen::Vector2d q = isometric(e);
      plot.directions.push_back({std::string(1, static_cast<char>('X' + a)), q.x(), q.y()});
    }
  } else {
    plot.x = {std::string(1, names[u]), "mm", {}, {}};
    plot.y = {std::string(1, names[v]), "mm", {}, {}};
  }
  auto project = [&](const Eigen::Vector3d& p) {
    return iso ? isometric(p) : Eigen::Vector2d(p[u], p[v]);
  };
  Series nominal;
  nominal.name = "nominal";
  nominal.colour = "#555555";
  nominal.style = SeriesStyle::dashed;
  nominal.width = 1.0;
  for (const auto& p : r.nominal) {
    const Eigen::Vector2d q = project(p);
    nominal.x.push_back(q.x());
    nominal.y.push_back(q.y());
  }
  plot.series.push_back(std::move(nominal));
  for (std::size_t m = 0; m < r.models.size(); ++m) {
    Series s;
    s.name = fmt::format("predicted {} (× {:g})", model_name(r.models[m]), k);
    s.colour = model_colour(r.models[m]);
    s.width = 1.4;
    // dual's first order is ae-arm: dashed, so that both stay visible.
    if (model::descriptor(r.models[m]).dashed) s.style = SeriesStyle::dashed;
    for (std::size_t i = 0; i < r.nominal.size(); ++i) {
      const Eigen::Vector2d q = project(r.nominal[i] + k * 1e-3 * r.deviation_um[m][i]);
      s.x.push_back(q.x());
      s.y.push_back(q.y());
      s.hover.push_back(hover_text(r, m, i));
    }
    plot.series.push_back(std::move(s));
  }
  plot.max_hover_targets = 1500;
  return plot;
}

LinePlot deviation_plot(const PredictedPath& r, std::size_t m) {
  LinePlot plot;
  plot.id = "deviation-" + model_name(r.models[m]);
  plot.title = fmt::format("Deviation along the path, {} model", model_name(r.models[m]));
  plot.x = {"path length", "mm", {}, {}};
  plot.y = {"deviation", "µm", {}, {}};
  const char* names[] = {"dx", "dy", "dz"};
  const char* colours[] = {"#d62728", "#2ca02c", "#1f77b4"};
  for (int a = 0; a < 3; ++a) {
    Series s;
    s.name = names[a];
    s.colour = colours[a];
    s.width = 1.2;
    for (std::size_t i = 0; i < r.nominal.size(); ++i) {
      s.x.push_back(r.path_length[i]);
      s.y.push_back(r.deviation_um[m][i][a]);
    }
    plot.series.push_back(std::move(s));
  }
  Series d;
  d.name = "|d|";
  d.colour = "#000000";
  d.width = 1.8;
  for (std::size_t i = 0; i < r.nominal.size(); ++i) {
    d.x.push_back(r.path_length[i]);
    d.y.push_back(r.deviation_um[m][i].norm());
    d.hover.push_back(hover_text(r, m, i));
  }
  plot.series.push_back(std::move(d));
  return plot;
}

LinePlot comparison_plot(const PredictedPath& r) {
  LinePlot plot;
  plot.id = "deviation-models";
  plot.title = "|d| along the path, all models";
  plot.x = {"path length", "mm", {}, {}};
  plot.y = {"|d|", "µm", {}, {}};
  for (std::size_t m = 0; m < r.models.size(); ++m) {
    Series s;
    s.name = model_name(r.models[m]);
    s.colour = model_colour(r.models[m]);
    s.style = model::descriptor(r.models[m]).dashed ? SeriesStyle::dashed : SeriesStyle::line;
    for (std::size_t i = 0; i < r.nominal.size(); ++i) {
      s.x.push_back(r.path_length[i]);
      s.y.push_back(r.deviation_um[m][i].norm());
      s.hover.push_back(hover_text(r, m, i));
    }
    plot.series.push_back(std::move(s));
  }
  return plot;
}

}  // namespace

Eigen::Vector2d isometric(const Eigen::Vector3d& p) {
  const double c = std::cos(M_PI / 6.0), s = std::sin(M_PI / 6.0);
  return {(p.y() - p.x()) * c, p.z() - (p.x() + p.y()) * s};
}

double auto_exaggeration(const PredictedPath& r) {
  if (r.nominal.empty()) return 1.0;
  Eigen::Vector3d lo = r.nominal.front(), hi = lo;
  for (const auto& p : r.nominal) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double extent = (hi - lo).maxCoeff();
  double max_mm = 0.0;
  for (const auto& s : r.stats) max_mm = std::max(max_mm, 1e-3 * s.max_um);
  if (!(max_mm > 0.0) || !(extent > 0.0)) return 1.0;
  const double raw = 0.04 * extent / max_mm;
  if (raw <= 1.0) return 1.0;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / mag;
  return mag * (f >= 5.0 ? 5.0 : f >= 2.0 ? 2.0 : 1.0);
}

void render_predict_report(HtmlPage& page, const PredictedPath& r, double k) {
  if (!(k > 0.0) || !std::isfinite(k)) k = auto_exaggeration(r);
  page.add_fact("program", r.program);
  page.add_fact("machine", r.machine);
  page.add_fact("points", std::to_string(r.total_points));

  page.add_section("summary", "Summary");
  Table t;
  t.id = "summary-table";
  t.caption = "Predicted deviation of the tool tip over all points, per model";
  t.header = {"model",        "max |dx| (µm)", "max |dy| (µm)", "max |dz| (µm)",
              "rms |d| (µm)", "max |d| (µm)",  "at line",       "out-of-range lookups"};
  for (const auto& s : r.stats)
    t.rows.push_back({model_name(s.model), fmt::format("{:.3f}", s.max_abs_um.x()),
                      fmt::format("{:.3f}", s.max_abs_um.y()),
                      fmt::format("{:.3f}", s.max_abs_um.z()), fmt::format("{:.3f}", s.rms_um),
                      fmt::format("{:.3f}", s.max_um), std::to_string(s.max_line),
                      std::to_string(s.out_of_range_lookups)});
  page.add_table(t);
  if (r.stride > 1)
    page.add_note(fmt::format(
        "{} points in all; the plots show every {}th ({} points); the table covers all points.",
        r.total_points, r.stride, r.nominal.size()));

  page.add_section("toolpath", "Toolpath: nominal and predicted");
  page.add_paragraph(fmt::format(
      "The predicted toolpath is drawn as nominal + {:g} × deviation, so that errors of a few µm "
      "become visible (the nominal path is dashed). Hover over a predicted path for the source "
      "line and the deviation.",
      k));
  page.add_figures({toolpath_plot(r, k, "toolpath-iso",
                                  fmt::format("Isometric view, deviation × {:g}", k), 0, 1, true)
                        .render(900, 640)});
  page.add_figures(
      {toolpath_plot(r, k, "toolpath-xy", fmt::format("XY plane, deviation × {:g}", k), 0, 1, false)
           .render(440, 420),
       toolpath_plot(r, k, "toolpath-xz", fmt::format("XZ plane, deviation × {:g}", k), 0, 2, false)
           .render(440, 420),
       toolpath_plot(r, k, "toolpath-yz", fmt::format("YZ plane, deviation × {:g}", k), 1, 2, false)
           .render(440, 420)});

  page.add_section("deviation", "Deviation along the path");
  page.add_paragraph(
      "Components dx, dy, dz and the length |d| of the predicted deviation P' − P against the "
      "length travelled along the path (rapids included). Hover over |d| for the source line.");
  std::vector<std::string> figs;
  if (r.models.size() > 1) figs.push_back(comparison_plot(r).render(900, 360));
  for (std::size_t m = 0; m < r.models.size(); ++m)
    figs.push_back(deviation_plot(r, m).render(900, 360));
  page.add_figures(figs);
}

}  // namespace abbe::report
