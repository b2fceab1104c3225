#include "abbe/diagnose/statistics.hpp"

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/non_central_chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>

namespace abbe::diagnose {

double normal_upper_quantile(double alpha) {
  const boost::math::normal_distribution<double> z;
  return boost::math::quantile(boost::math::complement(z, alpha));
}

double chi2_upper_quantile(int k, double alpha) {
  const boost::math::chi_squared_distribution<double> chi2(static_cast<double>(k));
  return boost::math::quantile(boost::math::complement(chi2, alpha));
}

double noncentral_chi2_upper_quantile(int k, double lambda, double alpha) {
  if (!(lambda > 0.0)) return chi2_upper_quantile(k, alpha);
  const boost::math::non_central_chi_squared_distribution<double> d(static_cast<double>(k), lambda);
  return boost::math::quantile(boost::math::complement(d, alpha));
}

}  // namespace abbe::diagnose
