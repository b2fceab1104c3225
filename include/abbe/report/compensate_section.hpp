#pragma once
// The compensate report: an original program and its compensated version
// (the output of `abbe compensate`) side by side — the nominal path, the
// predicted path of the original and the predicted path of the compensated
// program — and how far each predicted path lies from the nominal one.
//
// The distance of a predicted compensated point to the nominal path is taken
// to the nearest point of the original's path fragmented finely (0.2 mm, so
// that arcs are followed to < 1 µm for radii ≥ 5 mm), searched in a window
// that moves along the path. Rapids are included (compensation corrects
// their end points only, so their intermediate points may stay off).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "abbe/compensate/path_verifier.hpp"
#include "abbe/report/html_page.hpp"
#include "abbe/report/predicted_path.hpp"

namespace abbe::report {

struct CompensationComparison {
  PredictedPath original;     // nominal = the original's points
  PredictedPath compensated;  // nominal = the compensated program's points
  // Per kept point of `compensated`: the nearest point of the nominal path
  // to the predicted compensated point, and predicted − nearest (µm).
  std::vector<Eigen::Vector3d> nearest;
  std::vector<Eigen::Vector3d> residual_um;
  double residual_max_um = 0.0;
  double residual_rms_um = 0.0;
  std::size_t residual_max_line = 0;  // line of the compensated program
  // The same over the kept points on rapids only.
  std::size_t rapid_points = 0;
  double rapid_max_um = 0.0, rapid_rms_um = 0.0;
  std::size_t rapid_max_line = 0;
  // The cutting moves compared as `abbe verify` compares them (its numbers).
  compensate::VerifyStats verify;
};

// Both texts go through the same machine and the one model of `options`.
// Throws abbe::InputError on bad input.
CompensationComparison compare_compensation(const machine::Machine& machine,
                                            const std::string& original_text,
                                            const std::string& original_file,
                                            const std::string& compensated_text,
                                            const std::string& compensated_file,
                                            const PredictPathOptions& options);

// `exaggerate` ≤ 0: automatic (from the original's deviation).
void render_compensate_report(HtmlPage& page, const CompensationComparison& c, double exaggerate);

}  // namespace abbe::report
