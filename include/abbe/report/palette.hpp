#pragma once
// The colours of the reports: a colour-blind-safe set (the Okabe–Ito
// colours without their green, so no red/green pair appears anywhere), the
// colour of each model's curves, and the scale of |d| against a tolerance
// used by the 3-D toolpath (blue shades within the tolerance, orange to
// dark brown above it).
#include <string>

#include "abbe/model/model_kind.hpp"

namespace abbe::report::palette {

inline constexpr const char* kBlue = "#0072b2";
inline constexpr const char* kOrange = "#e69f00";
inline constexpr const char* kSky = "#56b4e9";
inline constexpr const char* kVermilion = "#d55e00";
inline constexpr const char* kPurple = "#cc79a7";
inline constexpr const char* kBlack = "#000000";
inline constexpr const char* kGrey = "#555555";

// Curve colour of a model (htm orange, ae-arm blue, dual purple, further
// models the next series colours).
std::string model_colour(model::ModelKind k);

// Colour of |d| / tolerance: 0 … 1 light to dark blue, 1 … 2 orange to
// vermilion, above 2 dark brown; NaN grey.
std::string tolerance_colour(double ratio);

}  // namespace abbe::report::palette
