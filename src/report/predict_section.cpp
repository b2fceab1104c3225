#include "abbe/report/predict_section.hpp"

#include <fmt/format.h>

#include <cmath>

#include "abbe/report/line_plot.hpp"
#include "abbe/report/palette.hpp"
#include "abbe/report/svg.hpp"
#include "abbe/report/toolpath_view.hpp"

namespace abbe::report {
namespace {

std::string model_colour(model::ModelKind k) { return palette::model_colour(k); }

std::string model_name(model::ModelKind k) { return model::to_string(k); }

// One model's deviations at the kept points as a plot draws them: the
// absolute ones, or those after the part's set-up.
struct ModelCurves {
  std::size_t model = 0;
  const std::vector<Eigen::Vector3d>* d = nullptr;
  const std::vector<Eigen::Vector3d>* u = nullptr;  // null: no uncertainty
  std::string label;                                // in the hover text
};

ModelCurves absolute_curves(const PredictedPath& r, std::size_t m) {
  return {m, &r.deviation_um[m], r.has_uncertainty() ? &r.u_um[m] : nullptr,
          model_name(r.models[m])};
}

const char* method_name(pipeline::AlignMethod method) {
  return method == pipeline::AlignMethod::datums ? "datum (3-2-1)" : "best-fit";
}

ModelCurves aligned_curves(const PredictedPath& r, std::size_t m) {
  return {m, &r.aligned_um[m], r.u_aligned_um.empty() ? nullptr : &r.u_aligned_um[m],
          fmt::format("{} after {} alignment", model_name(r.models[m]),
                      method_name(r.alignment.method))};
}

std::string hover_text(const PredictedPath& r, const ModelCurves& c, std::size_t i) {
  const Eigen::Vector3d& d = (*c.d)[i];
  auto src = r.source.find(r.line[i]);
  std::string u;
  if (c.u) {
    const Eigen::Vector3d& ui = (*c.u)[i];
    u = fmt::format("\nu(d) = ({:.3f}, {:.3f}, {:.3f}) µm", ui.x(), ui.y(), ui.z());
  }
  return fmt::format(
             "line {}: {}\n{}: P = ({:.3f}, {:.3f}, {:.3f}) mm, s = {:.1f} mm\nd = ({:.3f}, "
             "{:.3f}, "
             "{:.3f}) µm, |d| = {:.3f} µm",
             r.line[i], src == r.source.end() ? "" : src->second, c.label, r.nominal[i].x(),
             r.nominal[i].y(), r.nominal[i].z(), r.path_length[i], d.x(), d.y(), d.z(), d.norm()) +
         u;
}

// At most about `n` of the kept points for the SVG plots: every k-th, and
// in each stretch of k the one of the largest |d| (any model) too.
std::vector<std::size_t> display_subset(const PredictedPath& r, std::size_t n) {
  const std::size_t count = r.nominal.size();
  std::vector<std::size_t> out;
  const std::size_t k = std::max<std::size_t>(1, (count + n - 1) / n);
  auto dmax = [&](std::size_t i) {
    double v = 0.0;
    for (const auto& d : r.deviation_um) v = std::max(v, d[i].norm());
    return v;
  };
  for (std::size_t i = 0; i < count; i += k) {
    out.push_back(i);
    std::size_t best = i;
    for (std::size_t j = i + 1; j < std::min(count, i + k); ++j)
      if (dmax(j) > dmax(best)) best = j;
    if (best != i) out.push_back(best);
  }
  return out;
}

constexpr std::size_t kPlotPoints = 1500;

// |d| of a model along the path at the shown points, with hover text.
Series norm_series(const PredictedPath& r, const ModelCurves& c,
                   const std::vector<std::size_t>& shown) {
  Series s;
  for (std::size_t i : shown) {
    s.x.push_back(r.path_length[i]);
    s.y.push_back((*c.d)[i].norm());
    s.hover.push_back(hover_text(r, c, i));
  }
  return s;
}

// dx, dy, dz and |d| of one model along the path; with the uncertainty, the
// band d ± U (U = k·u) of each component under the curves.
LinePlot deviation_plot(const PredictedPath& r, const std::vector<std::size_t>& shown,
                        const ModelCurves& c, std::string id, std::string title) {
  LinePlot plot;
  plot.id = std::move(id);
  plot.title = std::move(title);
  plot.x = {"path length", "mm", {}, {}};
  plot.y = {"deviation", "µm", {}, {}};
  const char* names[] = {"dx", "dy", "dz"};
  const char* colours[] = {palette::kBlue, palette::kOrange, palette::kPurple};
  const std::vector<Eigen::Vector3d>& d = *c.d;
  if (c.u) {
    const double k = r.uncertainty.coverage_factor;
    for (int a = 0; a < 3; ++a) {
      Band band;
      band.name = a == 0 ? fmt::format("± U (k = {:g})", k) : "";
      band.colour = colours[a];
      for (std::size_t i : shown) {
        const double v = d[i][a], u = k * (*c.u)[i][a];
        band.x.push_back(r.path_length[i]);
        band.lo.push_back(v - u);
        band.hi.push_back(v + u);
      }
      plot.bands.push_back(std::move(band));
    }
  }
  for (int a = 0; a < 3; ++a) {
    Series s;
    s.name = names[a];
    s.colour = colours[a];
    s.width = 1.2;
    for (std::size_t i : shown) {
      s.x.push_back(r.path_length[i]);
      s.y.push_back(d[i][a]);
    }
    plot.series.push_back(std::move(s));
  }
  Series n = norm_series(r, c, shown);
  n.name = "|d|";
  n.colour = "#000000";
  n.width = 1.8;
  plot.series.push_back(std::move(n));
  plot.max_hover_targets = 100;
  return plot;
}

LinePlot absolute_plot(const PredictedPath& r, const std::vector<std::size_t>& shown,
                       std::size_t m) {
  const std::string name = model_name(r.models[m]);
  return deviation_plot(r, shown, absolute_curves(r, m), "deviation-" + name,
                        fmt::format("Deviation along the path, {} model", name));
}

LinePlot aligned_plot(const PredictedPath& r, const std::vector<std::size_t>& shown,
                      std::size_t m) {
  const std::string name = model_name(r.models[m]);
  return deviation_plot(
      r, shown, aligned_curves(r, m), "aligned-deviation-" + name,
      fmt::format("Deviation after {} alignment, {} model", method_name(r.alignment.method), name));
}

LinePlot comparison_plot(const PredictedPath& r, const std::vector<std::size_t>& shown) {
  LinePlot plot;
  plot.id = "deviation-models";
  plot.title = "|d| along the path, all models";
  plot.x = {"path length", "mm", {}, {}};
  plot.y = {"|d|", "µm", {}, {}};
  for (std::size_t m = 0; m < r.models.size(); ++m) {
    Series s = norm_series(r, absolute_curves(r, m), shown);
    s.name = model_name(r.models[m]);
    s.colour = model_colour(r.models[m]);
    s.style = model::descriptor(r.models[m]).dashed ? SeriesStyle::dashed : SeriesStyle::line;
    plot.series.push_back(std::move(s));
  }
  plot.max_hover_targets = 150;
  return plot;
}

// The part after its set-up (`--align`): per model the figures of the part
// (its cutting points) before and after the alignment, ± U with the draws,
// and the rigid motion of the set-up.
void render_part_table(HtmlPage& page, const PredictedPath& r) {
  const pipeline::PartAlignmentSummary& a = r.alignment;
  std::string how = std::string(method_name(a.method)) + " alignment";
  if (a.method == pipeline::AlignMethod::datums)
    how += fmt::format(" from the primary ({} points), secondary ({}) and tertiary ({}) datums",
                       a.datum_points[0], a.datum_points[1], a.datum_points[2]);
  Table t = make_table(
      "part-table",
      fmt::format("The part ({} cutting points) before and after its set-up: {} (the figures "
                  "of `abbe predict --align`)",
                  a.part_points, how),
      {"model", "deviation", "points", "max |dx| (µm)", "max |dy| (µm)", "max |dz| (µm)",
       "rms |d| (µm)", "max |d| (µm)", "at line", "set-up rotation (µrad)", "centroid shift (µm)"});
  auto vec = [](const Eigen::Vector3d& v, int digits) {
    return fmt::format("({:.{}f}, {:.{}f}, {:.{}f})", v.x(), digits, v.y(), digits, v.z(), digits);
  };
  const bool uncertain = r.has_uncertainty();
  for (std::size_t m = 0; m < a.models.size(); ++m) {
    const pipeline::ModelAlignment& ma = a.models[m];
    const pipeline::ModelUncertainty* mu = uncertain ? &r.uncertainty.models[m] : nullptr;
    auto row = [&](const pipeline::ModelStats& s, const char* what,
                   const pipeline::GroupUncertainty* u, bool setup) {
      if (u && u->points != s.points) u = nullptr;  // not the same points
      auto num = [&](double v, std::size_t f) {
        if (s.points == 0) return std::string("-");
        if (u) return fmt::format("{:.3f} ± {:.3f}", v, u->figures[f].expanded);
        return fmt::format("{:.3f}", v);
      };
      t.rows.push_back(
          {model_name(ma.kind), what, std::to_string(s.points), num(s.max_abs_um.x(), 0),
           num(s.max_abs_um.y(), 1), num(s.max_abs_um.z(), 2), num(s.rms_um(), 3), num(s.max_um, 4),
           s.points == 0 ? "-" : std::to_string(s.max_line), setup ? vec(ma.rotation_urad, 3) : "",
           setup ? vec(ma.centroid_shift_um, 4) : ""});
    };
    // The part's absolute figures are those of its cutting points.
    row(ma.absolute, "absolute", mu ? &mu->cutting : nullptr, false);
    row(ma.aligned, "after alignment", mu ? &mu->aligned : nullptr, true);
  }
  page.add_table(t);
  page.add_note(
      "After alignment: the deviation T(P + d) − P that remains once the predicted part is set "
      "up and inspected as a CMM does, T the rigid motion of the set-up (its rotation as a "
      "rotation vector; the centroid shift is T(c) − c at the part's centroid c). What the set-up "
      "removes (a constant offset and a rigid rotation) costs no accuracy on the part." +
      std::string(uncertain ? " Values ± U: the part set up again in every draw." : ""));
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

void render_predict_report(HtmlPage& page, const PredictedPath& r, double k, double tolerance_um) {
  if (!(k > 0.0) || !std::isfinite(k)) k = auto_exaggeration(r);
  page.add_facts(
      {{"program", r.program}, {"machine", r.machine}, {"points", std::to_string(r.total_points)}});

  page.add_section("summary", "Summary");
  Table t = make_table(
      "summary-table",
      "Predicted deviation of the tool tip per model: cutting moves, rapids and all points (the "
      "rows of `abbe predict`)",
      {"model", "moves", "points", "max |dx| (µm)", "max |dy| (µm)", "max |dz| (µm)",
       "rms |d| (µm)", "max |d| (µm)", "at line", "out-of-range lookups"});
  // `u`: the figures with their expanded uncertainty (null: none).
  auto row = [&](const ModelPathStats& s, const char* moves, bool lookups,
                 const pipeline::GroupUncertainty* u) {
    const bool none = s.points == 0;
    auto num = [&](double v, std::size_t f) {
      if (none) return std::string("-");
      if (u) return fmt::format("{:.3f} ± {:.3f}", v, u->figures[f].expanded);
      return fmt::format("{:.3f}", v);
    };
    t.rows.push_back({model_name(s.model), moves, std::to_string(s.points),
                      num(s.max_abs_um.x(), 0), num(s.max_abs_um.y(), 1), num(s.max_abs_um.z(), 2),
                      num(s.rms_um, 3), num(s.max_um, 4), none ? "-" : std::to_string(s.max_line),
                      lookups ? std::to_string(s.out_of_range_lookups) : ""});
  };
  const bool uncertain = r.has_uncertainty();
  for (std::size_t m = 0; m < r.stats.size(); ++m) {
    const pipeline::ModelUncertainty* mu = uncertain ? &r.uncertainty.models[m] : nullptr;
    if (m < r.cutting_stats.size())
      row(r.cutting_stats[m], "cutting", false, mu ? &mu->cutting : nullptr);
    if (m < r.rapid_stats.size()) row(r.rapid_stats[m], "rapid", false, mu ? &mu->rapid : nullptr);
    row(r.stats[m], "all", true, mu ? &mu->all : nullptr);
  }
  page.add_table(t);
  if (uncertain)
    page.add_note(fmt::format(
        "Values ± U, the expanded uncertainty U = k·u (k = {:g}) propagated from the campaign's "
        "uncertainty by Monte Carlo (GUM Supplement 1: {} draws, seed {}); propagated: {}. The "
        "plots of the deviation draw the band d ± U of dx, dy and dz.",
        r.uncertainty.coverage_factor, r.uncertainty.draws, r.uncertainty.seed,
        r.uncertainty.sources));
  if (r.stride > 1)
    page.add_note(fmt::format(
        "{} points in all; drawn: every {}th and the largest |d| of each stretch of {} ({} "
        "points in the 3-D view, at most {} per curve in the plots); the table covers all points.",
        r.total_points, r.stride, r.stride, r.nominal.size(), 2 * kPlotPoints));
  if (r.has_alignment()) {
    page.add_section("part", "The part after its set-up");
    render_part_table(page, r);
  }

  page.add_section("toolpath", "Toolpath: nominal and predicted");
  ToolpathViewOptions vo;
  vo.exaggerate = k;
  vo.tolerance_um = tolerance_um;
  page.add_paragraph(fmt::format(
      "The predicted toolpath drawn as nominal + {:g} × deviation (the nominal path dashed grey), "
      "coloured by |d| of the chosen model against the tolerance ({:g} µm; change it below). "
      "Drag to rotate, wheel or +/− to zoom, the buttons for the isometric view and the planes; "
      "hover over the path for the source line and the deviation.",
      k, tolerance_um > 0.0 ? tolerance_um : auto_tolerance(r)));
  page.add_html(render_toolpath_view(r, vo));

  page.add_section("deviation", "Deviation along the path");
  page.add_paragraph(
      "Components dx, dy, dz and the length |d| of the predicted deviation P' − P against the "
      "length travelled along the path (rapids included). Hover over |d| for the source line.");
  if (r.has_alignment())
    page.add_paragraph(fmt::format(
        "Beside each model's plot, the deviation after the part's {} alignment, T(P + d) − P "
        "(the set-up is fitted over the cutting points; rapids are drawn with the same T){}.",
        method_name(r.alignment.method),
        r.u_aligned_um.empty() ? "" : ", with its band ± U from the draws"));
  std::vector<std::string> figs;
  const std::vector<std::size_t> shown = display_subset(r, kPlotPoints);
  if (r.models.size() > 1) figs.push_back(comparison_plot(r, shown).render(900, 360));
  for (std::size_t m = 0; m < r.models.size(); ++m) {
    figs.push_back(absolute_plot(r, shown, m).render(900, 360));
    if (r.has_alignment()) figs.push_back(aligned_plot(r, shown, m).render(900, 360));
  }
  page.add_figures(figs);
}

}  // namespace abbe::report
