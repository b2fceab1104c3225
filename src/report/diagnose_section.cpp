#include "abbe/report/diagnose_section.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "abbe/diagnose/overlay.hpp"
#include "abbe/report/line_plot.hpp"
#include "abbe/report/palette.hpp"

namespace abbe::report {
namespace {

// Residual per observation against variable v (0..2 = s_x..s_z, 3 = t).
Series residual_series(const diagnose::Problem& p, int v, const std::string& name,
                       const std::string& colour, double radius) {
  Series s;
  s.name = name;
  s.colour = colour;
  s.style = SeriesStyle::markers;
  s.width = radius;
  const std::size_t n = std::min(p.obs.size(), static_cast<std::size_t>(p.y.size()));
  const std::size_t stride = std::max<std::size_t>(1, n / 6000);  // at most ~6000 markers
  for (std::size_t k = 0; k < n; k += stride) {
    const diagnose::PointContext& c = p.points[p.obs[k].point];
    s.x.push_back(v < 3 ? c.s[v] : c.t);
    s.y.push_back(p.y[static_cast<Eigen::Index>(k)]);
  }
  return s;
}

}  // namespace

DiagnosisForReport diagnose_for_report(const machine::Machine& machine,
                                       const io::MeasuredData& data,
                                       const diagnose::DiagnoseOptions& options) {
  DiagnosisForReport r;
  // The diagnosis as `abbe diagnose` makes it (the travel check, the
  // tables' uncertainty where asked), then its residual before and after.
  r.diagnosis = diagnose::diagnose(machine, data, options);
  r.before = diagnose::build_problem(machine, data, options.model, options.extend);
  const diagnose::Overlay overlay = diagnose::make_overlay(r.diagnosis, options.extend);
  r.after = diagnose::build_problem(machine, data, options.model, &overlay);
  // The datum (offsets, plate rotations) is fitted with the effects but is
  // not in the overlay (a new measurement has a new one): take it out, so the
  // residual after the extension is the one the diagnosis reports.
  for (std::size_t o = 0; o < r.after.obs.size(); ++o) {
    const diagnose::Observation& ob = r.after.obs[o];
    for (const diagnose::SelectedTerm& st : r.diagnosis.datum)
      r.after.y[static_cast<Eigen::Index>(o)] -=
          ob.u.dot(st.term.evaluate(r.after.points[ob.point]));
  }
  return r;
}

void render_diagnose_report(HtmlPage& page, const DiagnosisForReport& r) {
  const diagnose::Diagnosis& d = r.diagnosis;
  page.add_facts({{"measured", d.measured_file},
                  {"machine", d.machine},
                  {"model", d.model},
                  {"points", std::to_string(d.n_points)}});

  page.add_section("summary", "Models and the extension");
  Table t =
      make_table("diagnose-models", "Residual |measured − predicted| over the measured points",
                 {"model", "rms (µm)", "max (µm)"});
  for (const auto& m : d.models)
    t.rows.push_back({m.model, fmt::format("{:.3f}", m.rms_um), fmt::format("{:.3f}", m.max_um)});
  t.rows.push_back({d.model + " (diagnosed)", fmt::format("{:.3f}", d.baseline.rms_um),
                    fmt::format("{:.3f}", d.baseline.max_um)});
  t.rows.push_back({d.model + " + effects", fmt::format("{:.3f}", d.extended.rms_um),
                    fmt::format("{:.3f}", d.extended.max_um)});
  page.add_table(t);
  if (const std::string w = diagnose::travel_warning(d); !w.empty()) page.add_note(w);
  page.add_paragraph(fmt::format(
      "Held-out check ({} folds): rms {:.3f} µm without the effects, {:.3f} µm with them, a gain "
      "of {:.1f} %. Noise estimate after the fit: {:.3f} µm per observation.",
      d.folds, d.baseline_holdout_rms_um, d.holdout_rms_um, d.gain_percent, d.noise_um));
  if (!d.noise_method.empty() && d.noise_method != "none")
    page.add_paragraph(fmt::format("Noise from the data alone ({}): {:.3f} µm per observation.",
                                   d.noise_method, d.noise_independent_um));
  else if (d.noise_method == "none")
    page.add_paragraph(
        "Noise from the data alone: not available (no repeated points, no runs of equally spaced "
        "points).");
  if (!d.datum.empty()) {
    std::string datum;
    for (const auto& st : d.datum)
      datum += fmt::format("{}{} = {:.3g} ± {:.2g}", datum.empty() ? "" : "; ", st.term.label(),
                           st.term.coef.empty() ? 0.0 : st.term.coef[0],
                           st.term.stderr_.empty() ? 0.0 : st.term.stderr_[0]);
    page.add_paragraph("Datum of the measurement (always fitted, not an effect): " + datum + ".");
  }

  Table e;
  e.id = "diagnose-effects";
  e.caption = "Effects found, by importance";
  e.header = {"#", "kind", "axis", "value ± u", "explained", "unique", "shared", "description"};
  e.last_column_text = true;
  const char* axes = "XYZ";
  for (std::size_t i = 0; i < d.effects.size(); ++i) {
    const auto& term = d.effects[i].term;
    const bool ambiguous = !d.effects[i].ambiguous_with.empty();
    const char* status = ambiguous                   ? "ambiguous: "
                         : !d.effects[i].significant ? "not significant: "
                                                     : "";
    e.rows.push_back({std::to_string(i + 1), status + std::string(diagnose::kind_id(term.kind)),
                      term.axis >= 0 && term.axis < 3 ? std::string(1, axes[term.axis]) : "-",
                      diagnose::effect_value_text(term),
                      fmt::format("{:.1f} %", 100.0 * d.effects[i].explained_fraction),
                      fmt::format("{:.1f} %", 100.0 * d.effects[i].unique_fraction),
                      fmt::format("{:.1f} %", 100.0 * d.effects[i].shared_fraction),
                      term.description() + [&] {
                        const std::string lp = diagnose::linear_part_text(d.effects[i]);
                        const std::string pu = diagnose::period_unresolved_text(d.effects[i]);
                        const std::string up = diagnose::uncertainty_parts_text(d.effects[i]);
                        return (lp.empty() ? lp : "; " + lp) + (pu.empty() ? pu : "; " + pu) +
                               (up.empty() ? up : "; " + up);
                      }()});
  }
  page.add_table(e);
  if (d.tables.draws > 0)
    page.add_paragraph(fmt::format(
        "Every u holds the data's and the tables' uncertainty, √(data² + tables²): {} draws of "
        "the campaign ({}).",
        d.tables.draws, d.tables.sources));
  if (d.effects.empty()) page.add_note("No effect stands out of the noise.");
  if (d.isotropic.found) page.add_paragraph(diagnose::isotropic_text(d));
  if (!d.blind_spots.empty()) {
    Table b = make_table("diagnose-blind-spots",
                         "Not testable with these data (the design's blind spots)",
                         {"effect", "why", "what would add it"});
    for (const diagnose::BlindSpot& spot : d.blind_spots)
      b.rows.push_back({spot.what, spot.reason, spot.measure});
    page.add_table(b);
  }
  if (!d.circles.empty()) page.add_paragraph(diagnose::dynamic_text(d));
  if (!d.outliers.empty()) {
    Table o = make_table(
        "diagnose-outliers",
        fmt::format("Gross outliers: {} points with a residual beyond {:.3g} µm ({:g} robust σ of "
                    "the fit), left out of the fit and the noise estimates",
                    d.outliers.size(), d.outlier_threshold_um, d.outlier_k),
        {"line", "set", "x (mm)", "y (mm)", "z (mm)", "residual (µm)"});
    constexpr std::size_t kRows = 500;
    for (std::size_t i = 0; i < d.outliers.size() && i < kRows; ++i) {
      const auto& p = d.outliers[i];
      o.rows.push_back({p.line ? std::to_string(p.line) : "-", p.set.empty() ? "-" : p.set,
                        fmt::format("{:.3f}", p.s.x()), fmt::format("{:.3f}", p.s.y()),
                        fmt::format("{:.3f}", p.s.z()), fmt::format("{:+.2f}", p.residual_um)});
    }
    page.add_table(o);
    if (d.outliers.size() > kRows)
      page.add_note(fmt::format("{} more outliers are listed in the JSON report (--out).",
                                d.outliers.size() - kRows));
  }

  page.add_section("residuals", "Residual against each variable");
  page.add_paragraph(
      "Each marker is one measured deviation component (measured − predicted, along the "
      "measured direction), before (red) and after (blue) the selected effects are added to the "
      "model. A pattern that the extension removes is an effect the laser tables do not hold.");
  const char* names[] = {"s_x", "s_y", "s_z", "t"};
  const char* units[] = {"mm", "mm", "mm", "s"};
  std::vector<std::string> figs;
  for (int v = 0; v < 4; ++v) {
    LinePlot p;
    p.id = fmt::format("residual-{}", v < 3 ? std::string(1, "xyz"[v]) : std::string("t"));
    p.title = fmt::format("Residual against {}", names[v]);
    p.x = {names[v], units[v], {}, {}};
    p.y = {"residual", "µm", {}, {}};
    p.series = {residual_series(r.before, v, "before", palette::kOrange, 2.2),
                residual_series(r.after, v, "after the extension", palette::kBlue, 1.8)};
    figs.push_back(p.render(660, 340));
  }
  page.add_figures(figs);
}

}  // namespace abbe::report
