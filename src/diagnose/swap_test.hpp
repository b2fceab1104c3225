#pragma once
// The swap test of the design checks (design_ambiguity.cpp,
// cycle_period_test.cpp): an effect and a stand-in each added to
// everything else of the fit.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "abbe/diagnose/residuals.hpp"
#include "span.hpp"

namespace abbe::diagnose::design {

using Mat = Eigen::MatrixXd;

// A swap test of effect e: what it removes given everything else of the fit
// (the datum and the other effects), the one-column χ² margin at `alpha`,
// and what a stand-in removes in its place (span::SwapBasis).
struct SwapTest : span::SwapBasis {
  bool valid = false;
  double margin = 0.0;
};

SwapTest swap_test(const Problem& pb, const Mat& D, const std::vector<Mat>& cols, std::size_t e,
                   double alpha);
// The same beside the datum and the effects `others` marks only.
SwapTest swap_test(const Problem& pb, const Mat& D, const std::vector<Mat>& cols, std::size_t e,
                   double alpha, std::vector<bool> others);

// Appends `alt` to the effect's alternatives unless it is there.
void add_alternative(SelectedTerm& st, const std::string& alt);

}  // namespace abbe::diagnose::design
