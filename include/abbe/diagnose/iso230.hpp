#pragma once
// ISO 230-2:2014 evaluation of bidirectional laser runs (the parameters of
// the thesis' Tables 4–6): per target the mean unidirectional deviations
// x̄↑ x̄↓ (mean over the runs at that target), the estimators s↑ s↓, the
// reversal B_i = x̄↑ − x̄↓; per component A, R, B, mean reversal, E, M.
// Input: the runs CSV `axis,component,target_mm,run,direction,deviation`
// (docs/formats.md, "ISO 230-2 runs").
#include <istream>
#include <string>
#include <vector>

namespace abbe::diagnose {

struct Iso230Reading {
  char axis = 'X';
  std::string component;  // "EXX", "EBX", …
  double target_mm = 0.0;
  int run = 1;
  int dir = +1;            // +1 up (fwd), −1 down (rev)
  double deviation = 0.0;  // µm or µrad
  std::size_t line = 0;    // CSV line, for messages
};

struct Iso230Target {
  double target_mm = 0.0;
  int n_up = 0, n_down = 0;
  double mean_up = 0.0, mean_down = 0.0;  // x̄↑, x̄↓
  double s_up = 0.0, s_down = 0.0;        // s↑, s↓
  double reversal = 0.0;                  // B_i = x̄↑ − x̄↓
  double mean = 0.0;                      // x̄_i = (x̄↑ + x̄↓)/2
  double repeatability = 0.0;             // R_i = max(2s↑ + 2s↓ + |B_i|, R↑_i, R↓_i)
};

// Values that do not apply (bidirectional values of a one-direction
// component, the values of a missing direction) are NaN.
struct Iso230Result {
  char axis = 'X';
  std::string component;
  std::string unit;  // "um" or "urad"
  bool has_up = false, has_down = false;
  int runs = 0;                        // smallest number of runs of one direction at one target
  std::vector<Iso230Target> targets;   // ascending target position
  double A = 0, A_up = 0, A_down = 0;  // accuracy
  double R = 0, R_up = 0, R_down = 0;  // repeatability
  double B = 0, B_mean = 0;            // reversal value, mean reversal value
  double E = 0, E_up = 0, E_down = 0;  // systematic positioning error
  double M = 0;                        // mean bidirectional positioning error
};

// Reads the runs CSV; throws abbe::InputError (file, line, column) on bad input.
std::vector<Iso230Reading> read_iso230_runs(std::istream& in, const std::string& file);
// Evaluates every (axis, component) in order of first appearance; throws
// abbe::InputError (naming the file and component) when a target has fewer
// than 2 runs of a direction the component uses, or duplicate runs.
std::vector<Iso230Result> evaluate_iso230(const std::vector<Iso230Reading>& readings,
                                          const std::string& file);

std::string iso230_to_json(const std::vector<Iso230Result>& results, bool per_target);
std::string iso230_to_text(const std::vector<Iso230Result>& results);

}  // namespace abbe::diagnose
