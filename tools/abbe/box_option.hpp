#pragma once
// --box x0,y0,z0,x1,y1,z1: a box of tool-tip positions given by its two
// corners (lowest corner first), mm — the one form `abbe map` and
// `abbe simulate measure` accept (docs/identification.md, docs/virtual-machine.md).
#include <Eigen/Core>
#include <vector>

namespace abbe::cli {

inline constexpr const char* kBoxHelp =
    "Box of tool tips by its corners x0,y0,z0,x1,y1,z1 (mm, lowest corner first)";

// Sets lo and hi from the six values; an InputError (field --box) names the
// axis whose corner values are out of order.
void parse_box_option(const std::vector<double>& values, Eigen::Vector3d& lo, Eigen::Vector3d& hi);

}  // namespace abbe::cli
