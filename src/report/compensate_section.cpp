#include "abbe/report/compensate_section.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "abbe/gcode/program.hpp"
#include "abbe/path/fragmenter.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"
#include "abbe/pipeline/program_path.hpp"
#include "abbe/report/line_plot.hpp"
#include "abbe/report/palette.hpp"
#include "abbe/report/predict_section.hpp"

namespace abbe::report {
namespace {

// The nominal path of a program fragmented at `step`.
std::vector<Eigen::Vector3d> fine_path(const machine::Machine& machine, const std::string& text,
                                       const std::string& file, double step) {
  pipeline::PathOptions po;
  po.fragment.step = step;
  std::vector<Eigen::Vector3d> out;
  std::istringstream in(text);
  pipeline::run_path(in, file, pipeline::interpreter_config(machine), po,
                     [&](const path::PathPoint& p) { out.push_back(p.p); });
  return out;
}

// Nearest point of segment [a, b] to p.
Eigen::Vector3d nearest_on_segment(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& p) {
  const Eigen::Vector3d ab = b - a;
  const double l2 = ab.squaredNorm();
  if (!(l2 > 0.0)) return a;
  const double t = std::clamp((p - a).dot(ab) / l2, 0.0, 1.0);
  return a + t * ab;
}

const char* kNominal = "#555555";
const char* kOriginal = palette::kOrange;
const char* kCompensated = palette::kBlue;

}  // namespace

CompensationComparison compare_compensation(const machine::Machine& machine,
                                            const std::string& original_text,
                                            const std::string& original_file,
                                            const std::string& compensated_text,
                                            const std::string& compensated_file,
                                            const PredictPathOptions& options) {
  CompensationComparison c;
  std::istringstream a(original_text), b(compensated_text);
  c.original = predict_program(machine, a, original_file, options);
  // Corrections are µm: an axis moving less than 0.1 mm in a motion of the
  // compensated program keeps its direction (the original's motion had none).
  PredictPathOptions comp_options = options;
  comp_options.min_reversal_mm = 0.1;
  c.compensated = predict_program(machine, b, compensated_file, comp_options);
  const std::vector<Eigen::Vector3d> ref = fine_path(machine, original_text, original_file, 0.2);
  if (ref.empty()) return c;

  // Window search along the reference: from a little behind the last match
  // to far enough ahead for the largest step between kept points.
  std::size_t cursor = 0;
  double sum2 = 0.0;
  const auto& pts = c.compensated.nominal;
  for (std::size_t j = 0; j < pts.size(); ++j) {
    const Eigen::Vector3d predicted = pts[j] + 1e-3 * c.compensated.deviation_um[0][j];
    const double hop = j ? (pts[j] - pts[j - 1]).norm() : 0.0;
    const std::size_t ahead = 50 + static_cast<std::size_t>(hop / 0.2 * 1.5);
    const std::size_t lo = cursor > 50 ? cursor - 50 : 0;
    const std::size_t hi = std::min(ref.size() - 1, cursor + ahead);
    double best = std::numeric_limits<double>::infinity();
    Eigen::Vector3d best_q = ref[lo];
    std::size_t best_i = lo;
    for (std::size_t i = lo; i <= hi; ++i) {
      const Eigen::Vector3d q =
          i + 1 < ref.size() ? nearest_on_segment(ref[i], ref[i + 1], predicted) : ref[i];
      const double d = (q - predicted).squaredNorm();
      if (d < best) best = d, best_q = q, best_i = i;
    }
    cursor = best_i;
    const Eigen::Vector3d r = 1e3 * (predicted - best_q);
    c.nearest.push_back(best_q);
    c.residual_um.push_back(r);
    sum2 += r.squaredNorm();
    if (r.norm() > c.residual_max_um || j == 0)
      c.residual_max_um = r.norm(), c.residual_max_line = c.compensated.line[j];
  }
  c.residual_rms_um = pts.empty() ? 0.0 : std::sqrt(sum2 / static_cast<double>(pts.size()));
  double rapid2 = 0.0;
  for (std::size_t j = 0; j < pts.size(); ++j) {
    if (j >= c.compensated.rapid.size() || !c.compensated.rapid[j]) continue;
    const double d = c.residual_um[j].norm();
    rapid2 += d * d;
    if (d > c.rapid_max_um || c.rapid_points == 0)
      c.rapid_max_um = d, c.rapid_max_line = c.compensated.line[j];
    ++c.rapid_points;
  }
  c.rapid_rms_um = c.rapid_points ? std::sqrt(rapid2 / static_cast<double>(c.rapid_points)) : 0.0;
  // The cutting moves: verify's comparison itself.
  {
    std::istringstream comp(compensated_text), orig(original_text);
    const model::ErrorModel model(machine, options.models.front());
    compensate::VerifyOptions vo;
    vo.step = options.step;
    c.verify = compensate::verify_program(comp, compensated_file, orig, original_file,
                                          pipeline::interpreter_config(machine), model, vo);
  }
  return c;
}

void render_compensate_report(HtmlPage& page, const CompensationComparison& c, double k) {
  const PredictedPath& o = c.original;
  const PredictedPath& p = c.compensated;
  if (!(k > 0.0) || !std::isfinite(k)) k = auto_exaggeration(o);
  const std::string model = o.models.empty() ? "" : model::to_string(o.models.front());
  page.add_facts({{"original", o.program},
                  {"compensated", p.program},
                  {"machine", o.machine},
                  {"model", model}});

  page.add_section("summary", "Summary");
  Table t = make_table("compensate-table",
                       fmt::format("Predicted distance from the nominal path ({} model)", model),
                       {"program", "moves", "points", "rms (µm)", "max (µm)", "at line"});
  auto row = [&](const std::string& what, const char* moves, std::size_t n, double rms, double max,
                 std::size_t line) {
    const bool none = n == 0;
    t.rows.push_back({what, moves, std::to_string(n), none ? "-" : fmt::format("{:.3f}", rms),
                      none ? "-" : fmt::format("{:.3f}", max), none ? "-" : std::to_string(line)});
  };
  if (!o.cutting_stats.empty()) {
    const ModelPathStats& cs = o.cutting_stats[0];
    const ModelPathStats& rs = o.rapid_stats[0];
    row("original: predicted deviation |d|", "cutting", cs.points, cs.rms_um, cs.max_um,
        cs.max_line);
    row("original: predicted deviation |d|", "rapid", rs.points, rs.rms_um, rs.max_um, rs.max_line);
  }
  const compensate::VerifyStats& v = c.verify;
  row("compensated: predicted → nominal path (abbe verify)", "cutting", v.points, v.rms_um,
      v.max_um, v.max_line);
  row("compensated: nominal → predicted path (abbe verify)", "cutting", v.backward_points,
      v.backward_rms_um, v.backward_max_um, v.backward_max_line);
  row("compensated: predicted − nearest nominal", "rapid", c.rapid_points, c.rapid_rms_um,
      c.rapid_max_um, c.rapid_max_line);
  page.add_table(t);
  page.add_note(
      "Cutting moves (feeds, arcs, the feeds of canned cycles) and rapids are counted apart, as "
      "in `abbe predict` and `abbe verify`: the original's rows are predict's cutting and rapid "
      "rows; the compensated cutting rows are verify's own comparison (lines of the compensated "
      "program forward, of the original backward). Compensation corrects the end points of "
      "rapids only; their row gives the distance of the predicted rapid points to the nearest "
      "point of the original's nominal path (fragmented at 0.2 mm; at most the kept points).");

  page.add_section("toolpath", "Nominal, predicted original, predicted compensated");
  page.add_paragraph(fmt::format(
      "Deviations from the nominal path are drawn × {:g}: the predicted original as nominal + "
      "{:g} × d, the predicted compensated path as nearest nominal + {:g} × (predicted − "
      "nearest).",
      k, k, k));
  auto plot = [&](const std::string& id, const std::string& title, int u, int v, bool iso) {
    LinePlot pl;
    pl.id = id;
    pl.title = title;
    pl.equal_scale = true;
    const char* names = "xyz";
    if (iso) {
      pl.x = {"isometric horizontal", "mm", {}, {}};
      pl.y = {"isometric vertical", "mm", {}, {}};
      for (int a = 0; a < 3; ++a) {
        Eigen::Vector3d e = Eigen::Vector3d::Zero();
        e[a] = 1.0;
        const Eigen::Vector2d q = isometric(e);
        pl.directions.push_back({std::string(1, static_cast<char>('X' + a)), q.x(), q.y()});
      }
    } else {
      pl.x = {std::string(1, names[u]), "mm", {}, {}};
      pl.y = {std::string(1, names[v]), "mm", {}, {}};
    }
    auto proj = [&](const Eigen::Vector3d& q) {
      return iso ? isometric(q) : Eigen::Vector2d(q[u], q[v]);
    };
    Series n{"nominal", kNominal, SeriesStyle::dashed, 1.0, {}, {}, {}};
    Series so{fmt::format("predicted original (× {:g})", k),
              kOriginal,
              SeriesStyle::line,
              1.4,
              {},
              {},
              {}};
    Series sc{fmt::format("predicted compensated (× {:g})", k),
              kCompensated,
              SeriesStyle::line,
              1.4,
              {},
              {},
              {}};
    for (std::size_t i = 0; i < o.nominal.size(); ++i) {
      const Eigen::Vector2d a = proj(o.nominal[i]);
      const Eigen::Vector2d b = proj(o.nominal[i] + k * 1e-3 * o.deviation_um[0][i]);
      n.x.push_back(a.x()), n.y.push_back(a.y());
      so.x.push_back(b.x()), so.y.push_back(b.y());
    }
    for (std::size_t j = 0; j < p.nominal.size(); ++j) {
      const Eigen::Vector2d q = proj(c.nearest[j] + k * 1e-3 * c.residual_um[j]);
      sc.x.push_back(q.x()), sc.y.push_back(q.y());
      const auto src = p.source.find(p.line[j]);
      sc.hover.push_back(fmt::format("compensated line {}: {}\ndistance from nominal {:.3f} µm",
                                     p.line[j], src == p.source.end() ? "" : src->second,
                                     c.residual_um[j].norm()));
    }
    pl.series = {n, so, sc};
    return pl;
  };
  page.add_figures({plot("compensate-iso", fmt::format("Isometric view, × {:g}", k), 0, 1, true)
                        .render(900, 640)});
  page.add_figures(
      {plot("compensate-xy", fmt::format("XY plane, × {:g}", k), 0, 1, false).render(440, 420),
       plot("compensate-xz", fmt::format("XZ plane, × {:g}", k), 0, 2, false).render(440, 420),
       plot("compensate-yz", fmt::format("YZ plane, × {:g}", k), 1, 2, false).render(440, 420)});

  page.add_section("deviation", "Distance from the nominal path along the path");
  LinePlot d;
  d.id = "compensate-deviation";
  d.title = "Predicted distance from the nominal path";
  d.x = {"path length", "mm", {}, {}};
  d.y = {"distance", "µm", {}, {}};
  Series so{"original |d|", kOriginal, SeriesStyle::line, 1.5, {}, {}, {}};
  for (std::size_t i = 0; i < o.nominal.size(); ++i) {
    so.x.push_back(o.path_length[i]);
    so.y.push_back(o.deviation_um[0][i].norm());
  }
  Series sc{"compensated", kCompensated, SeriesStyle::line, 1.5, {}, {}, {}};
  for (std::size_t j = 0; j < p.nominal.size(); ++j) {
    sc.x.push_back(p.path_length[j]);
    sc.y.push_back(c.residual_um[j].norm());
    const auto src = p.source.find(p.line[j]);
    sc.hover.push_back(fmt::format("compensated line {}: {}\n{:.3f} µm", p.line[j],
                                   src == p.source.end() ? "" : src->second,
                                   c.residual_um[j].norm()));
  }
  d.series = {so, sc};
  page.add_figures({d.render(900, 360)});
}

}  // namespace abbe::report
