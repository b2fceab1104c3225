#pragma once
// Small statistics helpers of the diagnosis: upper quantiles of the normal
// and (noncentral) χ² distributions (for the significance and practical
// floors), from Boost.Math.
namespace abbe::diagnose {

// z with P(Z > z) = alpha for a standard normal Z (0 < alpha < 1).
double normal_upper_quantile(double alpha);
// c with P(χ²_k > c) = alpha (exact, Boost.Math; k ≥ 1).
double chi2_upper_quantile(int k, double alpha);
// c with P(χ²_k(λ) > c) = alpha for a noncentral χ² with k degrees of
// freedom and noncentrality λ ≥ 0 (λ = 0: the central quantile).
double noncentral_chi2_upper_quantile(int k, double lambda, double alpha);

}  // namespace abbe::diagnose
