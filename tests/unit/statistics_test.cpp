// Quantiles of the diagnosis' significance floor (Boost.Math), against
// tabulated values (NIST/SEMATECH e-Handbook, tables 1.3.6.7.1 and 1.3.6.7.4).
#include "abbe/diagnose/statistics.hpp"

#include <gtest/gtest.h>

using abbe::diagnose::chi2_upper_quantile;
using abbe::diagnose::normal_upper_quantile;

TEST(Statistics, NormalUpperQuantileMatchesTable) {
  EXPECT_NEAR(normal_upper_quantile(0.025), 1.959964, 1e-6);
  EXPECT_NEAR(normal_upper_quantile(0.05), 1.644854, 1e-6);
  EXPECT_NEAR(normal_upper_quantile(0.001), 3.090232, 1e-6);
  EXPECT_NEAR(normal_upper_quantile(0.5), 0.0, 1e-12);
  // Symmetry: z(1 - a) = -z(a).
  EXPECT_NEAR(normal_upper_quantile(0.9), -normal_upper_quantile(0.1), 1e-12);
}

TEST(Statistics, ChiSquaredUpperQuantileMatchesTable) {
  EXPECT_NEAR(chi2_upper_quantile(1, 0.05), 3.841, 1e-3);
  EXPECT_NEAR(chi2_upper_quantile(2, 0.01), 9.210, 1e-3);
  EXPECT_NEAR(chi2_upper_quantile(3, 0.05), 7.815, 1e-3);
  EXPECT_NEAR(chi2_upper_quantile(10, 0.001), 29.588, 1e-3);
  // k = 1 is the square of the two-sided normal quantile.
  const double z = normal_upper_quantile(0.005);
  EXPECT_NEAR(chi2_upper_quantile(1, 0.01), z * z, 1e-9);
}
