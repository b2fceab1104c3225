#pragma once
// The part set-ups the alignment tests use: a best fit, or 3-2-1 datums
// given as line sets of the program ("5-8", "5", "6").
#include "abbe/pipeline/aligned_prediction.hpp"

namespace abbe::test {

inline pipeline::AlignOptions best_fit_alignment() {
  pipeline::AlignOptions a;
  a.method = pipeline::AlignMethod::best_fit;
  return a;
}

inline pipeline::AlignOptions datum_alignment(const char* primary, const char* secondary,
                                              const char* tertiary) {
  pipeline::AlignOptions a;
  a.method = pipeline::AlignMethod::datums;
  a.primary = pipeline::LineSet::parse(primary, "--datum-primary");
  a.secondary = pipeline::LineSet::parse(secondary, "--datum-secondary");
  a.tertiary = pipeline::LineSet::parse(tertiary, "--datum-tertiary");
  return a;
}

}  // namespace abbe::test
