#pragma once
// The descriptors of the built-in effect kinds, one file each (private to
// the library; effect_catalogue.cpp registers them in this order).
#include <string>

#include "abbe/diagnose/effect_catalogue.hpp"

namespace abbe::diagnose::effects {

EffectDescriptor model_choice();
EffectDescriptor scale();
EffectDescriptor squareness();
EffectDescriptor reversal();
EffectDescriptor thermal_drift();
EffectDescriptor cyclic();
EffectDescriptor coupling();
EffectDescriptor arm_offset();
EffectDescriptor setup_offset();
EffectDescriptor setup_rotation();
EffectDescriptor unexplained();

// Helpers shared by the rows.
inline double coef_or_zero(const Term& t, std::size_t i) {
  return i < t.coef.size() ? t.coef[i] : 0.0;
}
// "[a, b, c]" with every digit of each number (the overlay's lists).
std::string yaml_list(const double* values, std::size_t n);
// Three numbers from the list under `key` (fails "<key> needs 3 numbers").
Eigen::Vector3d read_point(const OverlayFields& in, const char* key);

}  // namespace abbe::diagnose::effects
