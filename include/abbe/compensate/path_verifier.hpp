#pragma once
// verify_program: how far the predicted path of a compensated program lies
// from the nominal path of the original. Both programs stream through the
// front end side by side; only feed motions (G1, arcs, helices, the feeds
// of canned cycles) are compared — rapids are not cutting moves and are
// compensated at their written end coordinates only.
//  - forward: every fragment point c of the compensated program is
//    predicted (c + e(c)) and its distance to the nominal curve of the
//    original (lines, true arcs) is taken, searching the original's feed
//    motions from the current one a few ahead (the compensated program has
//    the same motions, some split into pieces);
//  - backward: every nominal fragment point n of the original is measured
//    to the predicted compensated curve that passes nearest.
// Direction signs for the bidirectional tables are the nominal motion's (as
// in the solver): the micro-motions a correction adds to an axis that is
// nominally at rest are not counted as reversals (docs/compensation.md).
#include <cstddef>
#include <istream>
#include <string>
#include <vector>

#include "abbe/gcode/interpreter.hpp"
#include "abbe/model/error_model.hpp"

namespace abbe::compensate {

struct VerifyOptions {
  double step = 5.0;        // fragment step, mm
  std::size_t window = 32;  // motions searched ahead of the current one
  double tol_um = 1.0;      // points farther than this are counted
  double slack = 0.05;      // curves matching within this of the best are candidates, mm
};

struct VerifyStats {
  std::size_t points = 0;  // forward points
  double max_um = 0.0;
  double rms_um = 0.0;
  std::size_t max_line = 0;  // line of the compensated program at the max
  std::size_t over_tol = 0;  // forward points farther than tol
  std::size_t backward_points = 0;
  double backward_max_um = 0.0;
  double backward_rms_um = 0.0;
  std::size_t backward_max_line = 0;  // line of the original at the backward max
  std::size_t backward_over_tol = 0;
  std::size_t out_of_range_lookups = 0;
  // Points with no feed curve of the other program to be measured to: the
  // other program has no (more) feed motions. They count as failures.
  std::size_t unmatched = 0;
  std::size_t backward_unmatched = 0;
};

// Why the programs do not pass at `tol_um` (empty: they pass): a distance
// beyond tol, points with nothing to match, or no feed points on a side —
// verify passes nothing it could not check.
std::vector<std::string> verify_failures(const VerifyStats& s, double tol_um);

VerifyStats verify_program(std::istream& compensated, const std::string& compensated_file,
                           std::istream& original, const std::string& original_file,
                           const gcode::InterpreterConfig& config, const model::ErrorModel& model,
                           const VerifyOptions& options);

}  // namespace abbe::compensate
