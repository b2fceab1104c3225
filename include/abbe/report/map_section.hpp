#pragma once
// The sections of the map report: statistics per model (mean, RMS and max
// |d| over the grid, htm against ae-arm) and colour maps of |d| on slices of
// the workspace — XY at the lowest, middle and highest z, XZ at the middle y,
// YZ at the middle x — with htm and ae-arm side by side on a shared colour
// scale (as in the AE-arm paper's workspace figure).
#include "abbe/identify/workspace_map.hpp"
#include "abbe/report/html_page.hpp"

namespace abbe::report {

void render_map_report(HtmlPage& page, const identify::WorkspaceMap& map,
                       const std::string& machine_name);

}  // namespace abbe::report
