#pragma once
// What measurement would tell an ambiguous effect from its rivals. When two
// explanations fit the measured points alike (their fitted contributions
// coincide, or a period aliases on the sampling), diagnose names neither;
// this says what to measure next so that they differ:
//   aliased periods             → sample that axis at irregular spacing;
//   squareness i→j against j→i  → (a rotation apart, the datum's) one
//                                  out-of-squareness: measure one axis's
//                                  direction against a reference;
//   one depends on time, one not → measure the points again in another
//                                  order or after a pause;
//   driven by different axes    → measure where those axes vary apart;
//   otherwise                   → measure where the explanations differ.
#include <string>
#include <vector>

#include "abbe/diagnose/term.hpp"

namespace abbe::diagnose {

// `rivals`: the alternatives that fit as well; `aliased_periods`: the other
// periods of a cyclic term that give the same samples. Empty when there is
// nothing to separate.
std::string separating_measurement(const Term& chosen, const std::vector<Term>& rivals,
                                   const std::vector<double>& aliased_periods);

}  // namespace abbe::diagnose
