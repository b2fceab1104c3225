#pragma once
// The interactive 3-D toolpath of the predict report: an HTML fragment with
// a canvas, the kept points as JSON and a small inline script (no library,
// nothing fetched). Drag to rotate, wheel or +/− to zoom, buttons for the
// isometric view and the XY, XZ and YZ planes; the path is drawn as
// nominal + K·deviation of the chosen model and coloured by |d| against a
// tolerance the reader can change (palette::tolerance_colour); hovering
// shows the source line, the point and the deviation. The script reports
// its state (view angles, zoom, hovered point) in data- attributes of the
// figure, which the browser test reads.
#include <string>

#include "abbe/report/predicted_path.hpp"

namespace abbe::report {

struct ToolpathViewOptions {
  std::string id = "toolpath-3d";
  double exaggerate = 1.0;    // K
  double tolerance_um = 0.0;  // ≤ 0: auto_tolerance
};

// The largest max |d| of the models rounded up to two significant digits,
// µm (1 µm when there is no deviation): every point within the tolerance,
// the blue shades showing how close each comes to the largest.
double auto_tolerance(const PredictedPath& path);

// The kept points as the JSON the script reads: {"k", "tol", "models",
// "p": [x, y, z, …] mm, "line": [...], "d": [[dx, dy, dz, …] µm per model],
// "src": {"line": "text"}}. Numbers are written with 3 decimals; '<' is
// escaped so the text cannot end the script element.
std::string toolpath_view_json(const PredictedPath& path, const ToolpathViewOptions& options);

std::string render_toolpath_view(const PredictedPath& path, const ToolpathViewOptions& options);

}  // namespace abbe::report
