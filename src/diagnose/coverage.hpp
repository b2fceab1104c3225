#pragma once
// What the data's layout lets a term see (internal to the diagnosis): each
// variable's range (s_x, s_y, s_z, t) and the approach directions seen, over
// all points and over the observations that measure each direction. The
// candidates (candidates.cpp) and the blind spots (blind_spots.cpp) read the
// same coverage, so what one leaves out the other lists.
#include <array>

#include "abbe/diagnose/residuals.hpp"

namespace abbe::diagnose {

class Coverage {
 public:
  explicit Coverage(const Problem& problem);

  // Variable v (0..2: s_x..s_z, 3: t) varies over all points.
  bool varies(int v) const { return all_[idx(v)].varies(); }
  // ... over the observations that measure direction i.
  bool varies_in(int v, int i) const { return in_[idx(i)][idx(v)].varies(); }
  // Axis j seen moving both ways (v_j < 0 and v_j > 0) at some points; at
  // the observations of direction i.
  bool reverses(int j) const { return signs_[idx(j)] == 3u; }
  bool reverses_in(int j, int i) const { return signs_in_[idx(i)][idx(j)] == 3u; }
  // Some point has a nonzero v_j.
  bool has_direction(int j) const { return signs_[idx(j)] != 0u; }
  // The lowest tool-tip coordinate p_j over all points (for messages).
  double tip_lo(int j) const { return tip_[idx(j)].lo; }

 private:
  struct Range {
    double lo = 1e300, hi = -1e300;
    void add(double x);
    bool varies() const { return hi - lo > 1e-9; }
  };
  static std::size_t idx(int k) { return static_cast<std::size_t>(k); }

  std::array<Range, 4> all_;
  std::array<std::array<Range, 4>, 3> in_;
  std::array<Range, 3> tip_;
  std::array<unsigned, 3> signs_{0, 0, 0};  // bit 0: v_j < 0 seen, bit 1: v_j > 0
  std::array<std::array<unsigned, 3>, 3> signs_in_{};
};

}  // namespace abbe::diagnose
