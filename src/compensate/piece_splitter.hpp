#pragma once
// How compensate splits one feed move: the solved points along it (nominal
// point and correction), and the longest pieces — straight lines, or arcs
// about the centre moved by the mean of their end corrections — that pass
// within a tolerance of the commanded point of every solved point between
// their ends (docs/compensation.md, Method, step 3).
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "abbe/gcode/motion.hpp"

namespace abbe::compensate::detail {

struct SolvedPoint {
  Eigen::Vector3d n;      // nominal, mm
  Eigen::Vector3d delta;  // c − n, mm (arriving here)
  double t = 0.0;         // parameter along the motion
  // A piece must end here: an in-plane axis of an arc reverses here, or a
  // reversal jump is taken up by here.
  bool reversal = false;
  // Leaving the point: differs from `delta` at a reversal whose correction
  // jump is taken by a micro move (a G1 from n + delta to n + delta_out).
  Eigen::Vector3d delta_out = Eigen::Vector3d::Zero();
  bool micro = false;
};

// True if one piece from sp[a] to sp[b] passes within tol_mm of the
// commanded point n + delta of every solved point between them.
bool piece_within(const gcode::Motion& m, const std::vector<SolvedPoint>& sp, std::size_t a,
                  std::size_t b, double tol_mm);

// The ends of the longest pieces within tol_mm (indices into sp, the last
// one sp.size() − 1), each as long as it stays within tol_mm and ending at
// every forced point (`reversal`). sp holds the start and at least one point.
void split_into_pieces(const gcode::Motion& m, const std::vector<SolvedPoint>& sp, double tol_mm,
                       std::vector<std::size_t>& breaks);

// Pieces shorter than min_len (commanded length; arcs: along the motion of
// length `len`) are merged with the next piece, or the previous one when a
// forced end follows, if the merged piece stays within tol_mm. Returns how
// many short pieces had to be kept (merging broke tol).
std::size_t merge_short_pieces(const gcode::Motion& m, const std::vector<SolvedPoint>& sp,
                               double len, double min_len, double tol_mm,
                               std::vector<std::size_t>& breaks);

}  // namespace abbe::compensate::detail
