#pragma once
// The candidate effects of a diagnosis (DESIGN.md §5): every catalogued kind
// per axis and direction where the data can show it, as Terms. Kinds with a
// nonlinear parameter (cyclic period, thermal time constant) are families
// whose parameter is searched over a grid at each selection step; the
// `unexplained` families are smooth (Legendre) functions of one variable or
// of a pair of variables per direction.
#include <vector>

#include "abbe/diagnose/residuals.hpp"
#include "abbe/diagnose/term.hpp"

namespace abbe::diagnose {

struct CandidateOptions {
  double min_period_mm = 4.0;    // cyclic periods searched in [min, max]
  double max_period_mm = 100.0;  // (pitch errors a 25–50 mm table under-samples)
  // And at most this share of the axis's measured span (0.5: two periods
  // on the travel; a 50 mm ballbar circle spans 100 mm of X and Y).
  double max_period_span_share = 0.5;
  std::vector<double> tau_s{300, 600, 900, 1200, 1800, 2700, 3600, 5400, 7200, 10800, 0};
  int single_degree = 6;  // unexplained: Legendre degree in one variable
  int pair_degree = 4;    // ... per variable of a pair
  // A reversal that grows along its travel (two columns: the jump and its
  // change along the axis; in the axis's own direction) is a candidate
  // beside the plain one where its growth sign(v_j)·(s_j − mid) is told
  // from the position s_j and the jump: on the observations of the
  // direction, after each set's mean (the datum), its multiple correlation
  // with the two is at most this (an axis driven one way over most of its
  // travel makes the growth a scale).
  bool growing_reversal = true;
  double max_growth_correlation = 0.5;
};

struct ScanFamily {
  Term base;                 // cyclic (period) or thermal_drift (tau) with the grid below
  std::vector<double> grid;  // periods (mm) or time constants (s)
};

struct CandidateSet {
  // The datum of the data (always fitted, never an effect): an offset per
  // `set` and measured direction, plus, for a set that lies in one plane
  // whose normal direction is not measured (a plate), its rotation in that
  // plane (docs/diagnosis.md, "Datum").
  std::vector<Term> datum;
  std::vector<Term> fixed;          // named kinds without a searched parameter
  std::vector<ScanFamily> scanned;  // named kinds with one
  std::vector<Term> generic;        // unexplained (direction = −1: one per present direction)
  int named_tests = 0;              // for the multiple-testing correction
  int generic_tests = 0;
};

CandidateSet build_candidates(const Problem& problem, const CandidateOptions& options);

}  // namespace abbe::diagnose
