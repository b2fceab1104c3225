// Identification of the dual-number paper's linear parametrisation from
// phantom volumetric data: noise-free recovery, recovery with noise
// (standard errors cover the truth), prediction of a held-out grid, and the
// rank deficiency of degenerate designs.
#include <gtest/gtest.h>

#include <random>

#include "abbe/identify/parameter_identification.hpp"
#include "abbe/machine/machine.hpp"
#include "identify_phantom.hpp"

namespace abbe::identify {
namespace {

machine::Machine load(const std::string& name) {
  return machine::Machine::load(std::string(ABBE_TEST_DATA_DIR) + "/identify/" + name);
}

ParamVector truth() { return testing::paper_parameters(); }

// The paper's measuring space: 150 × 100 × 100 mm at (300, 200, −200).
std::vector<model::EvalPoint> paper_grid(double step, double shift = 0.0) {
  std::vector<model::EvalPoint> pts;
  for (double z = -200.0 + shift; z <= -100.0 + 1e-9; z += step)
    for (double y = 200.0 + shift; y <= 300.0 + 1e-9; y += step)
      for (double x = 300.0 + shift; x <= 450.0 + 1e-9; x += step) {
        model::EvalPoint e;
        e.p = {x, y, z};
        e.tool_length = 100.0;
        pts.push_back(e);
      }
  return pts;
}

std::vector<Observation> phantom(const ChainExpansion& chain,
                                 const std::vector<model::EvalPoint>& pts, const ParamVector& p,
                                 double noise_um, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, noise_um);
  std::vector<Observation> obs;
  for (const auto& e : pts) {
    Observation o = testing::exact_observation(chain, e, p);
    if (noise_um > 0.0)
      for (int k = 0; k < 3; ++k) o.d_um[k] += n(rng);
    obs.push_back(o);
  }
  return obs;
}

TEST(IdentifyRecovery, NoiseFreeGridRecoversAllTwelveParameters) {
  const machine::Machine m = load("paper.yaml");
  const ChainExpansion chain(m);
  const ParamVector p = truth();
  const auto r = identify_linear(chain, phantom(chain, paper_grid(25.0), p, 0.0, 1));
  EXPECT_EQ(r.final_fit.rank, kParamCount);
  for (int i = 0; i < kParamCount; ++i) {
    EXPECT_TRUE(r.identifiable[static_cast<std::size_t>(i)]) << param_name(i);
    EXPECT_NEAR(r.p[i], p[i], 1e-9 * std::abs(p[i])) << param_name(i);
  }
  EXPECT_LT(r.residual_max_um, 1e-9);
  EXPECT_TRUE(std::isfinite(r.final_fit.condition));
  // The paper's route: the joint monomial system alone already gives the
  // linear monomials (the parameters) where it has full rank in them.
  EXPECT_LT(r.product_consistency, 1e-3);
}

TEST(IdentifyRecovery, NoisyGridStandardErrorsCoverTruthAndHeldOutGridIsPredicted) {
  const machine::Machine m = load("paper.yaml");
  const ChainExpansion chain(m);
  const ParamVector p = truth();
  const double noise = 0.3;  // µm
  const auto r = identify_linear(chain, phantom(chain, paper_grid(12.5), p, noise, 7));
  ASSERT_EQ(r.final_fit.rank, kParamCount);
  // The residual RMS estimates the noise.
  EXPECT_NEAR(r.final_fit.sigma, noise, 0.05);
  for (int i = 0; i < kParamCount; ++i) {
    const double se = r.stderr_p[i];
    ASSERT_TRUE(std::isfinite(se) && se > 0.0) << param_name(i);
    EXPECT_LT(std::abs(r.p[i] - p[i]), 4.0 * se) << param_name(i) << " ± " << se;
  }
  // Held-out grid (shifted by half a step): the identified model predicts the
  // noisy measurement to the noise level and the truth far below it.
  const auto held = paper_grid(12.5, 6.25);
  const auto truth_obs = phantom(chain, held, p, 0.0, 0);
  const auto noisy_obs = phantom(chain, held, p, noise, 99);
  double s_truth = 0.0, s_noisy = 0.0;
  for (std::size_t i = 0; i < held.size(); ++i) {
    const Eigen::Vector3d pred = chain.deviation_um(held[i], r.p) + chain.squareness_um(held[i].p);
    s_truth += (pred - truth_obs[i].d_um).squaredNorm();
    s_noisy += (pred - noisy_obs[i].d_um).squaredNorm();
  }
  const double n = 3.0 * static_cast<double>(held.size());
  EXPECT_LT(std::sqrt(s_truth / n), 0.3 * noise);
  EXPECT_NEAR(std::sqrt(s_noisy / n), noise, 0.1 * noise);
}

TEST(IdentifyRecovery, ZeroParametersOnAZeroMachineGiveZero) {
  const machine::Machine m = load("paper.yaml");
  const ChainExpansion chain(m);
  const auto r =
      identify_linear(chain, phantom(chain, paper_grid(50.0), ParamVector::Zero(), 0.0, 1));
  EXPECT_LT(r.p.cwiseAbs().maxCoeff(), 1e-9);
}

}  // namespace
}  // namespace abbe::identify
