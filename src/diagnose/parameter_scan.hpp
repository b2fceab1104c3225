#pragma once
// The parameter of a searched candidate family at one selection step,
// found by a quick projection on the residual before the best of the family
// is fitted exactly: the period of a cycle (the periodogram's peak on the
// frequency grid, refined by a parabola, with the other peaks that reach
// nearly its power as aliases) or the time constant of a drift (the largest
// normalised projection).
#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "candidate_fit.hpp"

namespace abbe::diagnose::selection {

struct ScanInput {
  const Problem& pb;
  const Mat& R;                            // point_sums of the residual
  const Mat& W;                            // point_sums' weights
  const std::vector<std::size_t>& set_of;  // each point's set (index in pb.sets)
  std::size_t stride = 1;                  // every stride-th point is used
  double alias_power = 0.9;                // SelectionOptions::alias_power
  bool refine_period = true;               // SelectionOptions::refine_period
  // The cycles the path has chosen: a cycle of the same axis and direction
  // is not scanned within 1/span of their frequencies (span: the axis's
  // measured travel), where two sinusoids are not resolved from each other
  // and a second one only takes up what the first's period left
  // (SelectionOptions::resolve_chosen_cycles; nullptr: none).
  const std::vector<Term>* chosen_cycles = nullptr;
};

// Per axis, the periodogram sums over the frequency grid, shared by the
// three directions of one step: [freq][dir][re, im].
using PowerCache = std::array<std::vector<double>, 3>;

// f.base with its searched parameter set; `aliases`: a cycle's other periods
// that fit these points as well.
Term scan_parameter(const ScanFamily& f, const ScanInput& in, PowerCache& power_cache,
                    std::vector<double>& aliases);

// The x in [lo, hi] where f is largest, by Brent's method
// (boost::math::tools::brent_find_minima, at most 60 evaluations) to `bits`
// bits of x: {x, f(x)}. Used for a cycle's frequency and a drift's ln τ.
std::pair<double, double> brent_maximum(const std::function<double(double)>& f, double lo,
                                        double hi, int bits);

// A cycle family's frequencies (1/mm): those of its period grid.
struct FrequencyRange {
  double lo = 0.0;
  double hi = std::numeric_limits<double>::infinity();
};
// The frequencies of f's grid (unbounded for an empty grid).
FrequencyRange frequency_range(const ScanFamily& f);

// A cycle's period refined on the exact ΔRSS beside span(Q) (r ⟂ Q):
// within ±half_step of the scan's estimate in frequency, 9 samples, then
// a Brent search (boost::math::tools::brent_find_minima, as a drift's τ)
// between the best sample's neighbours. The periodogram's peak is that of the raw projection on the
// (subsampled) residual; where sine and cosine are not orthogonal on the points (few or irregular
// levels) or the datum's columns take a part of the cycle, it lies a fraction of a lobe off the
// least-squares period, and over a long travel that fraction beats against the data: a second cycle
// at a neighbouring period is then needed for what the first left. c's
// term, columns and products are replaced when the refined period removes
// more (c's QtC must be Qᵀ·C), never outside `range` (the family's grid);
// where that holds it at the range's end, each of c's aliases within the
// range is refined too and the best kept (`aliases_at_range_end`).
// Returns what c removes then.
double refine_period_exactly(const Problem& pb, const Mat& Q, const Vec& r, double half_step,
                             Cached& c, FrequencyRange range = {},
                             bool aliases_at_range_end = false);

// The aliases of a chosen cycle c (removing d_pick) that these data do not
// reject: each is refined like the pick (refine_period_exactly, ±half_step)
// and kept, at its refined period, when it removes within `margin` of
// d_pick (one column's test, as for the other rivals). The periodogram's
// other peaks are only a shortlist: a true alias (the same samples) stays,
// but at irregular positions a sidelobe reaches 0.9 of the peak's power and
// can still fit far worse. Used where the axis's positions are not a few
// levels (SelectionOptions::alias_levels).
void confirm_aliases(const Problem& pb, const Mat& Q, const Vec& r, double half_step, double d_pick,
                     double margin, Cached& c, FrequencyRange range = {});

}  // namespace abbe::diagnose::selection
