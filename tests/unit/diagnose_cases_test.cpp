// Diagnosis cases beyond a single hidden effect: the model choice (data of
// the Abbe-consistent truth diagnosed with htm), an effect outside the
// catalogue (reported as unexplained with its variables), the virtual
// machine's own ballscrew cycle, the overlay round trip and --extend.
#include <gtest/gtest.h>

#include <cmath>

#include "abbe/diagnose/context.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/sim/effect.hpp"
#include "diagnose_vm_test.hpp"

namespace abbe::diagnose {
namespace {

using testing::full_box;
using testing::random_tips;
using testing::to_measured;

constexpr double kNoise = 0.5;

io::MeasuredData measure(const testing::VirtualMachine& vm, int n, std::uint64_t seed,
                         Eigen::Vector3d lo, Eigen::Vector3d hi) {
  const auto tips = random_tips(vm.generated.truth, n, seed, lo, hi);
  return to_measured(sim::measure(vm.generated.truth, tips, kNoise, seed + 7));
}

TEST(DiagnoseCases, HtmOnAbbeConsistentDataNamesModelChoice) {
  const auto& vm = testing::virtual_machine();
  Eigen::Vector3d lo, hi;
  full_box(vm.generated.truth, lo, hi);
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const io::MeasuredData data = measure(vm, 250, seed, lo, hi);
    DiagnoseOptions opt;
    opt.model = model::ModelKind::htm;
    const Diagnosis d = diagnose(vm.machine, data, opt);
    ASSERT_FALSE(d.effects.empty());
    EXPECT_EQ(d.effects.front().term.kind, TermKind::model_choice) << report_text(d);
    EXPECT_NEAR(d.effects.front().term.coef.at(0), 1.0, 0.05);  // the whole ae-arm difference
    EXPECT_GT(d.gain_percent, 80.0);
    // The same data diagnosed with ae-arm: no model_choice.
    const Diagnosis a = diagnose(vm.machine, data, DiagnoseOptions{});
    for (const auto& st : a.effects) EXPECT_NE(st.term.kind, TermKind::model_choice);
    ASSERT_EQ(d.models.size(), 3u);
    EXPECT_GT(d.models[0].rms_um, 3.0 * d.models[1].rms_um);  // htm vs ae-arm
  }
}

// d_X += A·sin(y/40 mm)·z/460 mm: no catalogued kind has this shape.
TEST(DiagnoseCases, EffectOutsideTheCatalogueIsUnexplainedInYAndZ) {
  const auto& vm = testing::virtual_machine();
  Eigen::Vector3d lo, hi;
  full_box(vm.generated.truth, lo, hi);
  lo.y() = -300.0;  // about 1.2 periods of sin(y/40)
  int ok = 0;
  const int n = 5;
  for (int i = 0; i < n; ++i) {
    io::MeasuredData data = measure(vm, 300, static_cast<std::uint64_t>(40 + i), lo, hi);
    for (auto& r : data.rows) r.d[0] += 10.0 * kNoise * std::sin(r.p.y() / 40.0) * r.p.z() / 460.0;
    const Diagnosis d = diagnose(vm.machine, data, DiagnoseOptions{});
    // The most important effect is the smooth function of (y, z) in X; a
    // named kind may take a small share (the z-linear part of the shape is
    // a catalogued form), never a large one.
    bool unexplained_yz = false, wrong_named = false;
    if (!d.effects.empty()) {
      const Term& t = d.effects.front().term;
      unexplained_yz =
          t.kind == TermKind::unexplained && t.direction == 0 && t.vars == std::vector<int>{1, 2};
    }
    for (const auto& st : d.effects)
      if (st.term.kind != TermKind::unexplained && st.explained_fraction > 0.05) wrong_named = true;
    if (unexplained_yz && !wrong_named)
      ++ok;
    else
      ADD_FAILURE() << report_text(d);
  }
  EXPECT_EQ(ok, n);
}

TEST(DiagnoseCases, FindsTheVirtualMachinesScrewCycle) {
  const auto& vm = testing::virtual_machine_with_screw_cycle();
  Eigen::Vector3d lo, hi;
  full_box(vm.generated.truth, lo, hi);
  const io::MeasuredData data = measure(vm, 400, 77, lo, hi);
  io::MeasuredData quiet = data;
  // The cycle (0.25 µm, in dx only: 0.10 µm RMS per observation) is below
  // the practical floor of 0.3 σ̂ per observation, so by default it is not
  // named; with the floor off the engine must still find it exactly.
  DiagnoseOptions opt;
  opt.selection.min_effect_rms = 0.0;
  const Diagnosis d = diagnose(vm.machine, data, opt);
  int cycles = 0;
  for (const auto& st : d.effects)
    if (st.term.kind == TermKind::cyclic && st.term.axis == st.term.direction) {
      ++cycles;
      EXPECT_NEAR(st.term.period_mm, 10.0, 0.1);
      EXPECT_NEAR(st.term.params()[0].second, 0.25, 0.1);  // amplitude, µm
    }
  EXPECT_GE(cycles, 2) << report_text(d);
}

TEST(DiagnoseCases, OverlayRoundTripAndExtendRemovesTheEffect) {
  const auto& vm = testing::virtual_machine();
  sim::TruthMachine truth = vm.generated.truth;
  truth.effects = {sim::parse_effect("reversal:Y:4um"),
                   sim::parse_effect("thermal_drift:Z:3um:tau=900")};
  Eigen::Vector3d lo, hi;
  full_box(truth, lo, hi);
  const auto tips = random_tips(truth, 300, 5, lo, hi);
  const io::MeasuredData data = to_measured(sim::measure(truth, tips, kNoise, 9));
  const Diagnosis d = diagnose(vm.machine, data, DiagnoseOptions{});
  ASSERT_GE(d.effects.size(), 2u) << report_text(d);
  const Overlay ov = make_overlay(d, nullptr);
  const Overlay back = Overlay::parse(ov.to_yaml(), "<overlay>");
  ASSERT_EQ(back.terms.size(), ov.terms.size());
  ContextBuilder cb(vm.machine, model::ModelKind::ae_arm);
  for (std::size_t i = 0; i < 20; ++i) {
    model::EvalPoint ep;
    ep.p = data.rows[i].p;
    ep.tool_length = data.rows[i].tool_length;
    ep.dir = data.rows[i].v;
    ep.time = data.rows[i].t;
    Eigen::Vector3d pred;
    const PointContext pc = cb.make(ep, data.rows[i].set, pred);
    EXPECT_LT((ov.evaluate(pc) - back.evaluate(pc)).norm(), 1e-9);
  }
  // Diagnosing again with the overlay as extension finds nothing more.
  DiagnoseOptions opt;
  opt.extend = &back;
  const Diagnosis again = diagnose(vm.machine, data, opt);
  EXPECT_TRUE(again.effects.empty()) << report_text(again);
  // The datum is always fitted: refitted on what the overlay leaves, it is
  // the datum of the joint fit, and the residual is the same.
  EXPECT_NEAR(again.extended.rms_um, d.extended.rms_um, 1e-6);
}

TEST(DiagnoseCases, OverlayErrorsNameTheField) {
  try {
    Overlay::parse(
        "format: abbe-overlay-1\nmodel: ae-arm\neffects:\n  - term: cyclic\n    axis: X\n"
        "    direction: Q\n    period_mm: 10\n    coef: [1, 2]\n",
        "o.yaml");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "o.yaml");
    EXPECT_EQ(e.where().line, 6u);
    EXPECT_EQ(e.where().field, "direction");
  }
  EXPECT_THROW(Overlay::parse("format: abbe-overlay-1\neffects:\n  - term: scale\n    axis: X\n"
                              "    direction: X\n    coef: [1, 2]\n",
                              "o.yaml"),
               InputError);
  EXPECT_THROW(Overlay::parse("effects: []\n", "o.yaml"), InputError);
}

}  // namespace
}  // namespace abbe::diagnose
