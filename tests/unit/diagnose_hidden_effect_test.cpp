// Hide one effect of the catalogue (kind, axis, magnitude 3–20× the noise,
// sign drawn at random) in virtual-machine data; the diagnosis must name it
// and reach ≥ 70 % of the held-out gain of an oracle fit of the true effect.
// Also: noise-only data name nothing; two effects of different kinds are
// both named.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>

#include "abbe/sim/effect.hpp"
#include "diagnose_vm_test.hpp"

namespace abbe::diagnose {
namespace {

using testing::full_box;
using testing::random_tips;
using testing::to_measured;
using testing::virtual_machine;

constexpr double kNoise = 0.5;  // µm
constexpr int kPoints = 250;

struct Hidden {
  sim::Effect effect;
  Term oracle;
};

// Largest |s_a| over the box (m), for effects given at the travel end.
double reach_m(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double L, int a) {
  const double add = a == 2 ? L : 0.0;
  return 1e-3 * std::max(std::abs(lo[a] + add), std::abs(hi[a] + add));
}

Hidden draw(std::mt19937_64& rng, const Problem* pb_for_travel) {
  (void)pb_for_travel;
  const auto& vm = virtual_machine();
  const sim::TruthMachine& truth = vm.generated.truth;
  Eigen::Vector3d lo, hi;
  full_box(truth, lo, hi);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int kind = static_cast<int>(rng() % 7);
  const int a = static_cast<int>(rng() % 3);
  const double f = 3.0 + 17.0 * u(rng);
  const double sign = u(rng) < 0.5 ? -1.0 : 1.0;
  const double mag = sign * f * kNoise;
  const char A = "XYZ"[a];
  Hidden h;
  std::string text;
  Term& o = h.oracle;
  o.axis = a;
  o.direction = a;
  switch (kind) {
    case 0:
      text = fmt::format("reversal:{}:{}um", A, mag);
      o.kind = TermKind::reversal;
      break;
    case 1:
      text = fmt::format("scale:{}:{}ppm", A, mag / reach_m(lo, hi, truth.tool_length, a));
      o.kind = TermKind::scale;
      break;
    case 2: {
      const double tau = 600.0 + 2400.0 * u(rng);
      o.kind = TermKind::thermal_drift;
      o.tau_s = tau;
      if (u(rng) < 0.5) {
        text = fmt::format("thermal_drift:{}:{}um:tau={}", A, mag, tau);
      } else {
        text = fmt::format("thermal_drift:{}:{}ppm:tau={}", A,
                           mag / reach_m(lo, hi, truth.tool_length, a), tau);
        o.with_axis = a;
      }
      break;
    }
    case 3: {
      const double period = 8.0 + 32.0 * u(rng);
      text = fmt::format("cyclic:{}:{}um:period={},phase={}", A, mag, period, 360.0 * u(rng));
      o.kind = TermKind::cyclic;
      o.period_mm = period;
      break;
    }
    case 4: {
      const int w = (a + 1 + static_cast<int>(rng() % 2)) % 3;
      const int d = static_cast<int>(rng() % 3);
      text = fmt::format("coupling:{}:{}um:with={},dir={}", A, mag, "XYZ"[w], "XYZ"[d]);
      o.kind = TermKind::coupling;
      o.axis = std::min(a, w);
      o.with_axis = std::max(a, w);
      o.direction = d;
      const auto& m = virtual_machine().machine;
      for (int k = 0; k < 3; ++k) {
        const auto& tr = m.travel(static_cast<machine::Axis>(k));
        o.centre[k] = 0.5 * (tr.min + tr.max);
        o.half[k] = 0.5 * (tr.max - tr.min);
      }
      break;
    }
    case 5: {
      // Δ along a direction ⟂ the axis, sized so that |ε_a × Δ| ≈ f·noise (RMS over the travel).
      const int d = (a + 1 + static_cast<int>(rng() % 2)) % 3;
      const auto& ax = truth.axes[static_cast<std::size_t>(a)];
      double ss = 0.0;
      for (int i = 0; i <= 20; ++i) {
        const double s = ax.travel_min + (ax.travel_max - ax.travel_min) * i / 20.0;
        ss += truth.rotation_urad(a, s, 0).cross(Eigen::Vector3d::Unit(d)).squaredNorm();
      }
      const double eps = std::sqrt(ss / 21.0);
      text = fmt::format("arm_offset:{}:{}mm:dir={}", A, mag / (1e-3 * eps), "XYZ"[d]);
      o.kind = TermKind::arm_offset;
      o.direction = d;
      break;
    }
    default: {
      if (u(rng) < 0.5) {
        text = fmt::format("setup:{}:{}um:set=run", A, mag);
        o.kind = TermKind::setup_offset;
        o.set = "run";
      } else {
        const Eigen::Vector3d c = 0.5 * (lo + hi);
        text = fmt::format("setup:{}:{}urad:set=run,cx={},cy={},cz={}", A, mag / 0.3, c.x(), c.y(),
                           c.z());
        o.kind = TermKind::setup_rotation;
        o.set = "run";
        o.centre = c;
      }
      break;
    }
  }
  h.effect = sim::parse_effect(text);
  return h;
}

struct Outcome {
  Diagnosis d;
  double oracle = 0.0;
};

Outcome run(const std::vector<sim::Effect>& effects, const std::vector<Term>& oracle,
            std::uint64_t seed, int points = kPoints) {
  const auto& vm = virtual_machine();
  sim::TruthMachine truth = vm.generated.truth;
  truth.effects = effects;
  Eigen::Vector3d lo, hi;
  full_box(truth, lo, hi);
  const auto tips = random_tips(truth, points, seed, lo, hi);
  const io::MeasuredData data = to_measured(sim::measure(truth, tips, kNoise, seed + 1000));
  const Problem pb = build_problem(vm.machine, data, model::ModelKind::ae_arm, nullptr);
  DiagnoseOptions opt;
  opt.selection.seed = seed;
  Outcome out;
  out.d = diagnose_problem(pb, opt);
  if (!oracle.empty()) out.oracle = testing::oracle_gain(pb, oracle, opt.selection.folds, seed);
  return out;
}

bool named(const Diagnosis& d, const Term& want) {
  // A hidden setup offset is the data's datum: always fitted, reported there.
  if (want.kind == TermKind::setup_offset)
    for (const auto& st : d.datum)
      if (st.term.kind == TermKind::setup_offset && st.term.axis == want.axis) return true;
  for (const auto& st : d.effects) {
    const Term& t = st.term;
    if (std::string(kind_id(t.kind)) != kind_id(want.kind)) continue;
    if (want.kind == TermKind::coupling) {
      if (t.axis == want.axis && t.with_axis == want.with_axis) return true;
    } else if (t.axis == want.axis) {
      return true;
    }
  }
  return false;
}

int seeds() {
  const char* s = std::getenv("ABBE_DIAGNOSE_SEEDS");  // the `slow` sweep sets 200
  return s ? std::max(1, std::atoi(s)) : 40;
}

TEST(DiagnoseHiddenEffect, NamesTheHiddenEffectAndReachesTheOracleGain) {
  const int n = seeds();
  int found = 0, gain_ok = 0;
  for (int i = 0; i < n; ++i) {
    std::mt19937_64 rng(static_cast<std::uint64_t>(1000 + i));
    const Hidden h = draw(rng, nullptr);
    const Outcome o = run({h.effect}, {h.oracle}, static_cast<std::uint64_t>(i + 1));
    const bool ok = named(o.d, h.oracle);
    found += ok ? 1 : 0;
    const double gain = o.d.gain_percent / 100.0;
    const bool g = gain >= 0.7 * o.oracle;
    gain_ok += g ? 1 : 0;
    if (!ok || !g) {
      std::string e;
      for (const auto& st : o.d.effects) e += " [" + st.term.label() + "]";
      std::cerr << "miss: seed " << i << ": hidden " << h.effect.text << (ok ? "" : " NOT named")
                << "; gain " << gain << " vs oracle " << o.oracle << "; found:" << e << "\n";
    }
  }
  // Individual misses are reported above; the requirement is the rate.
  EXPECT_GE(found, static_cast<int>(std::ceil(0.95 * n)));
  EXPECT_GE(gain_ok, static_cast<int>(std::ceil(0.95 * n)));
}

TEST(DiagnoseHiddenEffect, NoiseOnlyNamesNothing) {
  const int n = seeds() / 2;
  int clean = 0;
  for (int i = 0; i < n; ++i) {
    const Outcome o = run({}, {}, static_cast<std::uint64_t>(500 + i));
    if (o.d.effects.empty()) {
      ++clean;
    } else {
      std::string e;
      for (const auto& st : o.d.effects) e += " [" + st.term.label() + "]";
      std::cerr << "noise-only seed " << i << " named:" << e << "\n";
    }
  }
  EXPECT_GE(clean, static_cast<int>(std::ceil(0.95 * n)));
}

TEST(DiagnoseHiddenEffect, TwoEffectsOfDifferentKindsAreBothNamed) {
  for (std::uint64_t seed : {11u, 12u, 13u}) {
    const sim::Effect rev = sim::parse_effect("reversal:X:3um");
    const sim::Effect cyc = sim::parse_effect("cyclic:Y:2um:period=18,dir=Z");
    Term t_rev;
    t_rev.kind = TermKind::reversal;
    t_rev.axis = 0;
    t_rev.direction = 0;
    Term t_cyc;
    t_cyc.kind = TermKind::cyclic;
    t_cyc.axis = 1;
    t_cyc.direction = 2;
    t_cyc.period_mm = 18.0;
    const Outcome o = run({rev, cyc}, {t_rev, t_cyc}, seed);
    EXPECT_TRUE(named(o.d, t_rev)) << report_text(o.d);
    EXPECT_TRUE(named(o.d, t_cyc)) << report_text(o.d);
    EXPECT_GE(o.d.gain_percent / 100.0, 0.7 * o.oracle);
    for (const auto& st : o.d.effects)
      if (st.term.kind == TermKind::cyclic) {
        EXPECT_NEAR(st.term.period_mm, 18.0, 0.5);
      }
  }
}

}  // namespace
}  // namespace abbe::diagnose
