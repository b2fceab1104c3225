#pragma once
// The sections of the predict report: the summary table per model, the
// interactive 3-D toolpath (toolpath_view.hpp) with the deviation exaggerated (predicted' = nominal
// + K·deviation, as in the thesis' toolpath figures), and the deviation along the path per model
// with the source line on hover.
#include "abbe/report/html_page.hpp"
#include "abbe/report/predicted_path.hpp"

namespace abbe::report {

// K such that the largest deviation appears as about 4 % of the toolpath's
// extent, rounded down to 1, 2 or 5 × 10ⁿ (1 when there is no deviation).
double auto_exaggeration(const PredictedPath& path);

// Isometric drawing of a point: X to the lower left, Y to the lower right,
// Z up; mm along every axis.
Eigen::Vector2d isometric(const Eigen::Vector3d& p);

// `exaggerate` ≤ 0 chooses auto_exaggeration; `tolerance_um` ≤ 0 chooses
// auto_tolerance (the colour scale of the 3-D toolpath).
void render_predict_report(HtmlPage& page, const PredictedPath& path, double exaggerate,
                           double tolerance_um = 0.0);

}  // namespace abbe::report
