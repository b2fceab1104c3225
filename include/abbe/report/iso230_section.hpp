#pragma once
// The ISO 230-2 report: per (axis, component) the chart of the mean
// unidirectional deviations x̄↑ and x̄↓ at each target with their ± 2s
// bands (dashed) and the bidirectional mean, and the table of the
// parameters A, B, R, E and M (directional values too), as evaluated by
// diagnose::evaluate_iso230 (the same numbers as `abbe iso230`).
#include <vector>

#include "abbe/diagnose/iso230.hpp"
#include "abbe/report/html_page.hpp"

namespace abbe::report {

void render_iso230_report(HtmlPage& page, const std::vector<diagnose::Iso230Result>& results);

}  // namespace abbe::report
