#include "abbe/report/iso230_section.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <string>

#include "abbe/report/line_plot.hpp"
#include "abbe/report/palette.hpp"

namespace abbe::report {
namespace {

std::string unit_text(const std::string& u) { return u == "urad" ? "µrad" : "µm"; }

std::string value(double v) { return std::isfinite(v) ? fmt::format("{:.3f}", v) : "–"; }

std::string plot_id(const diagnose::Iso230Result& r) {
  std::string id = fmt::format("iso230-{}-{}", r.axis, r.component);
  for (char& c : id) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return id;
}

// One direction: the mean and the ± 2s curves.
void add_direction(LinePlot& plot, const diagnose::Iso230Result& r, bool up, const std::string& u) {
  const char* colour = up ? palette::kBlue : palette::kOrange;
  const char* arrow = up ? "↑" : "↓";
  Series mean, plus, minus;
  mean.name = fmt::format("mean x̄{}", arrow);
  mean.colour = colour;
  mean.width = 1.8;
  plus.name = fmt::format("x̄{0} ± 2s{0}", arrow);
  plus.colour = colour;
  plus.style = SeriesStyle::dashed;
  plus.width = 1.0;
  minus = plus;
  minus.name.clear();
  for (const auto& t : r.targets) {
    const double m = up ? t.mean_up : t.mean_down;
    const double s = up ? t.s_up : t.s_down;
    mean.x.push_back(t.target_mm);
    mean.y.push_back(m);
    mean.hover.push_back(
        fmt::format("target {:g} mm, {}: x̄{} = {:.3f} {}, s{} = {:.3f} {} ({} runs)", t.target_mm,
                    up ? "up" : "down", arrow, m, u, arrow, s, u, up ? t.n_up : t.n_down));
    plus.x.push_back(t.target_mm);
    plus.y.push_back(m + 2.0 * s);
    minus.x.push_back(t.target_mm);
    minus.y.push_back(m - 2.0 * s);
  }
  Series markers = mean;
  markers.name.clear();
  markers.style = SeriesStyle::markers;
  markers.width = 2.5;
  markers.hover.clear();
  plot.series.push_back(std::move(mean));
  plot.series.push_back(std::move(markers));
  plot.series.push_back(std::move(plus));
  plot.series.push_back(std::move(minus));
}

}  // namespace

void render_iso230_report(HtmlPage& page, const std::vector<diagnose::Iso230Result>& results) {
  page.add_fact("components", std::to_string(results.size()));
  page.add_section("iso230-summary", "ISO 230-2 parameters");
  Table t = make_table(
      "iso230-table",
      "Per component: accuracy A, repeatability R, reversal B (and mean reversal B̄), systematic "
      "error E, mean bidirectional error M; ↑ ↓ the unidirectional values",
      {"axis", "component", "unit", "runs", "A", "A↑", "A↓", "R", "R↑", "R↓", "B", "B̄", "E", "E↑",
       "E↓", "M"});
  for (const auto& r : results)
    t.rows.push_back({std::string(1, r.axis), r.component, unit_text(r.unit),
                      std::to_string(r.runs), value(r.A), value(r.A_up), value(r.A_down),
                      value(r.R), value(r.R_up), value(r.R_down), value(r.B), value(r.B_mean),
                      value(r.E), value(r.E_up), value(r.E_down), value(r.M)});
  page.add_table(t);
  page.add_note(
      "Values that do not apply (the bidirectional values of a component measured in one "
      "direction) are shown as –.");

  page.add_section("iso230-charts", "Deviation per target");
  page.add_paragraph(
      "Per component: the mean deviation of the runs at each target position, approaching in the "
      "positive (↑, blue) and negative (↓, orange) direction, with the band x̄ ± 2s of each "
      "direction dashed, as in ISO 230-2's charts. Hover over a point for its values.");
  std::vector<std::string> figs;
  for (const auto& r : results) {
    LinePlot p;
    p.id = plot_id(r);
    const std::string u = unit_text(r.unit);
    p.title = fmt::format("{} {}: A = {}, B = {}, R = {}, E = {}, M = {} {}", r.axis, r.component,
                          value(r.A), value(r.B), value(r.R), value(r.E), value(r.M), u);
    p.x = {fmt::format("target position {}", r.axis), "mm", {}, {}};
    p.y = {"deviation", u, {}, {}};
    if (r.has_up) add_direction(p, r, true, u);
    if (r.has_down) add_direction(p, r, false, u);
    if (r.has_up && r.has_down) {
      Series mean;
      mean.name = "bidirectional mean x̄";
      mean.colour = palette::kGrey;
      mean.width = 1.0;
      for (const auto& tg : r.targets) {
        mean.x.push_back(tg.target_mm);
        mean.y.push_back(tg.mean);
      }
      p.series.push_back(std::move(mean));
    }
    figs.push_back(p.render(560, 380));
  }
  page.add_figures(figs);
}

}  // namespace abbe::report
