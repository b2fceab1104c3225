#pragma once
// The report tests' machines and prediction: the rectangle program (rect_program.hpp)
// through predict_program with htm and ae-arm, seed 4, the given set-up,
// Monte Carlo draws and cap on the points kept for the plots.
#include <cstddef>
#include <sstream>
#include <string>

#include "abbe/machine/machine.hpp"
#include "abbe/pipeline/aligned_prediction.hpp"
#include "abbe/report/html_page.hpp"
#include "abbe/report/predict_section.hpp"
#include "abbe/report/predicted_path.hpp"
#include "rect_program.hpp"

namespace abbe::test {

// The sample machine without and with the campaign's uncertainty.
inline const std::string kPlainMachine = std::string(ABBE_TEST_DATA_DIR) + "/machines/sample.yaml";
inline const std::string kUncertainMachine =
    std::string(ABBE_SOURCE_DIR) + "/machines/sample/machine-uncertainty.yaml";

inline report::PredictedPath predict_rect(const std::string& machine_file,
                                          const pipeline::AlignOptions& align, std::size_t draws,
                                          std::size_t max_points) {
  const machine::Machine m = machine::Machine::load(machine_file);
  report::PredictPathOptions o;
  o.models = {model::ModelKind::htm, model::ModelKind::ae_arm};
  o.align = align;
  o.uncertainty_draws = draws;
  o.seed = 4;
  o.max_points = max_points;
  std::istringstream in(kRectProgram);
  return report::predict_program(m, in, "rect.ngc", o);
}

// The prediction's report page, dated 2026-01-01 so that it does not
// depend on the day it is made.
inline std::string rect_page(const report::PredictedPath& r) {
  report::HtmlPage page("abbe: predicted toolpath of rect.ngc");
  report::Provenance p;
  p.date = "2026-01-01T00:00:00Z";
  page.set_provenance(p);
  report::render_predict_report(page, r, 0.0);
  return page.render();
}

}  // namespace abbe::test
