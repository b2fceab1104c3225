// The design of the identification: the monomial expansion is the D₂ chain
// (checked against the project's dual ErrorModel on a tabulated copy of the
// parametrisation), and degenerate designs are reported as rank deficient.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <random>

#include "abbe/identify/parameter_identification.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"
#include "identify_phantom.hpp"

namespace abbe::identify {
namespace {

machine::Machine load(const std::string& name) {
  return machine::Machine::load(std::string(ABBE_TEST_DATA_DIR) + "/identify/" + name);
}

ParamVector random_params(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-40.0, 40.0);
  ParamVector p;
  for (int i = 0; i < kParamCount; ++i) p[i] = u(rng);
  return p;
}

// The tool tip at `p` with tool length `tool_length`.
model::EvalPoint at(const Eigen::Vector3d& p, double tool_length) {
  model::EvalPoint e;
  e.p = p;
  e.tool_length = tool_length;
  return e;
}

// A tool tip anywhere in the test machine's travel, tool length 100 mm.
model::EvalPoint random_point(std::mt19937& rng) {
  model::EvalPoint e;
  e.p = {std::uniform_real_distribution<double>(0, 754)(rng),
         std::uniform_real_distribution<double>(0, 500)(rng),
         std::uniform_real_distribution<double>(-550, -100)(rng)};
  e.tool_length = 100.0;
  return e;
}

TEST(IdentifyDesign, MonomialNamesAndIndices) {
  EXPECT_EQ(kMonomialCount, 90);
  EXPECT_EQ(monomial_name(3), "f1");
  EXPECT_EQ(monomial_name(product_index(3, 6)), "f1*g1");
  EXPECT_EQ(monomial_name(product_index(6, 3)), "f1*g1");
  EXPECT_EQ(monomial_name(product_index(0, 0)), "a^2");
  EXPECT_EQ(product_index(11, 11), kMonomialCount - 1);
  for (int k = 0; k < kMonomialCount; ++k) {
    int i = 0, j = 0;
    monomial_params(k, i, j);
    ASSERT_GE(i, 0);
    if (j >= 0) {
      EXPECT_EQ(product_index(i, j), k);
    }
  }
}

// rows · monomials(p) reproduces the chain at p (the expansion is exact).
TEST(IdentifyDesign, ExpansionReproducesTheChain) {
  const machine::Machine m = load("paper.yaml");
  const ChainExpansion chain(m);
  std::mt19937 rng(3);
  for (int t = 0; t < 20; ++t) {
    const ParamVector p = 50.0 * random_params(rng);  // large: the ε² part matters
    const model::EvalPoint e = random_point(rng);
    Eigen::Vector3d second;
    const Eigen::Vector3d d = chain.deviation_um(e, p, &second);
    const Eigen::Vector3d rebuilt = chain.monomials(e) * ChainExpansion::monomial_values(p);
    EXPECT_LT((d - rebuilt).norm(), 1e-9 * std::max(1.0, d.norm()));
    EXPECT_GT(second.norm(), 0.0);
  }
}

// The paper: "the coefficient of f1·g1 is in the form x·y²/2" (in Δx). The
// chain gives exactly that (×10⁻¹⁵ µm for f, g in µrad/m, x, y in mm), and
// nothing in Δy, Δz.
TEST(IdentifyDesign, ProductF1G1HasThePapersCoefficient) {
  const machine::Machine m = load("paper.yaml");
  const ChainExpansion chain(m);
  const int k = product_index(static_cast<int>(Param::f1), static_cast<int>(Param::g1));
  for (double x : {300.0, 450.0})
    for (double y : {200.0, 300.0})
      for (double z : {-200.0, -100.0}) {
        model::EvalPoint e;
        e.p = {x, y, z};
        e.tool_length = 100.0;
        const MonomialRows r = chain.monomials(e);
        EXPECT_NEAR(r(0, k), 1e-15 * x * y * y / 2.0, 1e-12 * 1e-15 * x * y * y);
        EXPECT_EQ(r(1, k), 0.0);
        EXPECT_EQ(r(2, k), 0.0);
      }
}

// The parametrised chain equals the project's dual ErrorModel on a component
// table that tabulates the parametrisation at 1 mm knots (the s²/2
// straightness is interpolated to h²/8 · f · 1e-6 µm).
TEST(IdentifyDesign, ChainMatchesDualErrorModelOnTabulatedParameters) {
  const machine::Machine base = load("paper.yaml");
  std::mt19937 rng(5);
  const ParamVector p = random_params(rng);
  std::string csv = "axis,component,position_mm,direction,value\n";
  for (int a = 0; a < 3; ++a) {
    const machine::Travel t = base.travel(machine::kAxes[static_cast<std::size_t>(a)]);
    for (double s = t.min; s <= t.max + 1e-9; s += 1.0) {
      Eigen::Vector3d sv = Eigen::Vector3d::Zero();
      sv[a] = s;
      const model::AxisErrors e = component_errors(p, sv)[static_cast<std::size_t>(a)];
      for (int d = 0; d < 6; ++d) {
        const double v = d < 3 ? e.delta_um[d] : e.theta_urad[d - 3];
        csv += fmt::format(
            "{},{},{},mean,{:.17g}\n", "XYZ"[a],
            machine::component_name({machine::kAxes[static_cast<std::size_t>(a)], d}), s, v);
      }
    }
  }
  machine::MachineSpec spec = base.spec();
  spec.table = machine::ComponentTable::parse(csv, "<tabulated>");
  const machine::Machine m(spec);
  const model::ErrorModel dual(m, model::ModelKind::dual);
  const ChainExpansion chain(base);
  model::ModelData data;
  for (int t = 0; t < 20; ++t) {
    const model::EvalPoint e = random_point(rng);
    Eigen::Vector3d second;
    const Eigen::Vector3d mine = chain.deviation_um(e, p, &second) + chain.squareness_um(e.p);
    const model::Deviation ref = dual.evaluate(e, data);
    EXPECT_LT((mine - ref.e_um).norm(), 1e-4) << t;
    EXPECT_LT((second - ref.second_order_um).norm(), 1e-9) << t;
  }
}

// The paper's own setting: x = 1…15, y = z = 5. Every y- and z-dependence is
// a constant there, so the 15-row systems cannot separate the parameters.
TEST(IdentifyDesign, PaperLineIsRankDeficientAndSaysWhich) {
  const machine::Machine m = load("paper.yaml");
  const ChainExpansion chain(m);
  const ParamVector p = testing::paper_parameters();
  std::vector<Observation> obs;
  for (int x = 1; x <= 15; ++x)
    obs.push_back(testing::exact_observation(chain, at({double(x), 5.0, 5.0}, 0.0), p));
  const auto r = identify_linear(chain, obs);
  for (const MonomialFit& f : r.per_component) {
    EXPECT_EQ(f.fit.rows, 15);
    EXPECT_LT(f.fit.rank, static_cast<int>(f.monomials.size()));
    EXPECT_FALSE(f.fit.null_space.empty());
  }
  EXPECT_LT(r.final_fit.rank, kParamCount);
  EXPECT_EQ(r.final_fit.null_space.size(),
            static_cast<std::size_t>(kParamCount - r.final_fit.rank));
  int unidentifiable = 0;
  for (bool b : r.identifiable) unidentifiable += b ? 0 : 1;
  EXPECT_GT(unidentifiable, 0);
  // Rank deficient, but the data are still reproduced.
  EXPECT_LT(r.residual_max_um, 1e-9);
  EXPECT_FALSE(std::isfinite(r.final_fit.condition));
}

// With every reference point on the spindle axis the roll of Z has no arm:
// h3 is reported as the one unidentifiable parameter.
TEST(IdentifyDesign, RollOfZWithoutArmIsReportedUnidentifiable) {
  const machine::Machine m = load("paper-on-axis.yaml");
  const ChainExpansion chain(m);
  const ParamVector p = testing::paper_parameters();
  std::vector<Observation> obs;
  for (double z = -200; z <= -100; z += 25)
    for (double y = 200; y <= 300; y += 25)
      for (double x = 300; x <= 450; x += 25)
        obs.push_back(testing::exact_observation(chain, at({x, y, z}, 100.0), p));
  const auto r = identify_linear(chain, obs);
  EXPECT_EQ(r.final_fit.rank, kParamCount - 1);
  for (int i = 0; i < kParamCount; ++i)
    EXPECT_EQ(r.identifiable[static_cast<std::size_t>(i)], i != static_cast<int>(Param::h3))
        << param_name(i);
  ASSERT_EQ(r.final_fit.null_space.size(), 1u);
  EXPECT_NEAR(std::abs(r.final_fit.null_space[0].direction[static_cast<int>(Param::h3)]), 1.0,
              1e-9);
  for (int i = 0; i < kParamCount; ++i)
    if (i != static_cast<int>(Param::h3)) {
      EXPECT_NEAR(r.p[i], p[i], 1e-9 * std::abs(p[i]));
    }
}

}  // namespace
}  // namespace abbe::identify
