#pragma once
// The smooth function's surplus (SelectionOptions::smooth_surplus_test):
// where no named part of the best smooth function's structure explains its
// share of it (name_ratio), a part still explains the structure when what
// the smooth function adds beside it passes none of the smooth function's
// own floors — the rest is the noise a wide function fits, or a structure
// below the floor (on a circle, the model's own table error beside a small
// scale).
#include <functional>
#include <string>
#include <vector>

#include "step.hpp"

namespace abbe::diagnose::selection {

// The part that explains the structure by its surplus, or nullptr. Tried:
// the structure's lead (`lead`, may be null) and the named candidates above
// their floors that move at least half along the smooth function's
// direction, whose fitted contribution the smooth function reproduces
// (≥ 0.9 of it: on a circle every position is a function of the angle and
// the pass, so the variables alone do not tell a part); not an arm offset
// (it carries the model's own table error) nor a cycle (its searched period
// fits a piece of any smooth structure). The one the smooth function adds
// least beside is tested. `smooth_columns`: the best smooth function's
// columns (st.g_best); `smooth_floor(k, s2)`: its floors for k columns at
// residual variance s2.
const Score* part_by_surplus(const Step& st, const Score* lead, const Mat& smooth_columns,
                             const std::function<double(int, double)>& smooth_floor, int step,
                             std::vector<std::string>& log);

}  // namespace abbe::diagnose::selection
