// Diagnosis speed: 100 k measured points of the virtual machine (two hidden
// effects, noise 0.5 µm) against the full candidate catalogue — residuals of
// the three models, candidates, stepwise selection with 5-fold held-out
// checks, final fit (docs/performance.md, "Diagnosis").
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>

#include "abbe/diagnose/diagnosis.hpp"
#include "abbe/io/measured_data.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/sim/effect.hpp"
#include "abbe/sim/laser_campaign.hpp"
#include "abbe/sim/truth_generator.hpp"
#include "abbe/sim/validation_measurement.hpp"

namespace {

struct Setup {
  abbe::sim::GeneratedMachine generated;
  abbe::machine::Machine machine;
  abbe::io::MeasuredData data;
};

// effects 0: a reversal of Y and a drift of Z (each a step of its own);
// 1: a coupling x·y→X with a scale X (one structure, dX(x, y), that a
// combination of the two explains: the structure search of step 3 with its
// leads and partners); 2: a cycle of X (a 2.5 µm pitch error of 16.3 mm)
// with a reversal of Y (a cycle chosen: its period scanned, refined on the
// exact ΔRSS and once more beside the other named terms in the final fit).
Setup make_setup(int points, int effects) {
  abbe::sim::GeneratorOptions go;
  go.seed = 7;
  go.noise_scale = 0.0;
  abbe::sim::GeneratedMachine g = abbe::sim::generate_machine(go);
  const abbe::sim::CampaignResult r = abbe::sim::run_campaign(g);
  const auto dir = std::filesystem::temp_directory_path() / "abbe_bench_diagnose";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "errors.csv") << abbe::sim::table_to_csv(r);
  abbe::machine::Machine m = abbe::machine::Machine::parse(
      abbe::sim::machine_to_yaml(g, r, "errors.csv"), "<bench>", dir.string());
  if (effects == 0)
    g.truth.effects = {abbe::sim::parse_effect("reversal:Y:3um"),
                       abbe::sim::parse_effect("thermal_drift:Z:4um:tau=1800")};
  else if (effects == 1)
    g.truth.effects = {abbe::sim::parse_effect("coupling:X:4um:with=Y,dir=X"),
                       abbe::sim::parse_effect("scale:X:6ppm")};
  else
    g.truth.effects = {abbe::sim::parse_effect("cyclic:X:2.5um:period=16.3"),
                       abbe::sim::parse_effect("reversal:Y:3um")};
  Eigen::Vector3d lo, hi;
  abbe::sim::default_box(g.truth, g.truth.tool_length, lo, hi);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<abbe::sim::TipState> tips;
  for (int i = 0; i < points; ++i) {
    abbe::sim::TipState t;
    for (int k = 0; k < 3; ++k) t.p[k] = lo[k] + (hi[k] - lo[k]) * u(rng);
    t.tool_length = g.truth.tool_length;
    for (auto& d : t.dir) d = u(rng) < 0.5 ? -1 : 1;
    t.time = 0.1 * i;
    t.set = "run";
    tips.push_back(t);
  }
  abbe::io::MeasuredData data =
      abbe::sim::to_measured_data(abbe::sim::measure(g.truth, tips, 0.5, 2), "<bench>");
  return Setup{std::move(g), std::move(m), std::move(data)};
}

// A regular grid of about `points` points in nx × ny × nz levels (at most
// 40 per axis: every axis levelled, design_ambiguity.hpp), walked level by
// level in order (time follows Z), 0.1 s per point; effects 0: a drift of
// Z; 1: a drift of X with a coupling y·z→X (a smooth dX(z,t) wins the
// first step: within a level y follows t).
Setup make_grid_setup(int points, int effects) {
  Setup s = make_setup(1, 0);
  if (effects == 0)
    s.generated.truth.effects = {abbe::sim::parse_effect("thermal_drift:Z:4um:tau=1800")};
  else
    s.generated.truth.effects = {abbe::sim::parse_effect("thermal_drift:X:8um:tau=2100"),
                                 abbe::sim::parse_effect("coupling:Y:6um:with=Z,dir=X")};
  Eigen::Vector3d lo, hi;
  abbe::sim::default_box(s.generated.truth, s.generated.truth.tool_length, lo, hi);
  const int nz = 35, ny = 38, nx = std::max(2, points / (ny * nz));
  std::vector<abbe::sim::TipState> tips;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        abbe::sim::TipState t;
        const int ii = j % 2 == 0 ? i : nx - 1 - i;
        t.p = {lo.x() + (hi.x() - lo.x()) * ii / (nx - 1.0),
               lo.y() + (hi.y() - lo.y()) * j / (ny - 1.0),
               hi.z() - (hi.z() - lo.z()) * k / (nz - 1.0)};
        t.tool_length = s.generated.truth.tool_length;
        t.dir = {j % 2 == 0 ? 1 : -1, 1, -1};
        t.time = 0.1 * static_cast<double>(tips.size());
        t.set = "grid";
        tips.push_back(t);
      }
  s.data = abbe::sim::to_measured_data(abbe::sim::measure(s.generated.truth, tips, 0.5, 3),
                                       "<bench grid>");
  return s;
}

// The paths the revisit of the first step ran (its log lines).
std::size_t revisits(const abbe::diagnose::Diagnosis& d) {
  return static_cast<std::size_t>(
      std::count_if(d.log.begin(), d.log.end(),
                    [](const std::string& l) { return l.rfind("revisit:", 0) == 0; }));
}

// range(0): points; range(1): 1 with the checks of what the design cannot
// tell apart (design_ambiguity.hpp), 0 without — their cost as a ratio;
// range(2): the hidden effects (make_grid_setup); range(3): 1 with the
// outlier flagging (outliers.hpp), 0 without; range(4): 1 with a chosen
// drift's τ refined between the scan grid's values (exact_tau and
// refine_tau, time_constant.hpp), 0 with the grid's τ.
void BM_DiagnoseGrid(benchmark::State& state) {
  const Setup s =
      make_grid_setup(static_cast<int>(state.range(0)), static_cast<int>(state.range(2)));
  abbe::diagnose::DiagnoseOptions o;
  o.design.levelled_axes = state.range(1) != 0;
  o.outliers.enabled = state.range(3) != 0;
  o.selection.exact_tau = o.selection.refine_tau = state.range(4) != 0;
  std::size_t effects = 0, revisited = 0;
  for (auto _ : state) {
    const abbe::diagnose::Diagnosis d = abbe::diagnose::diagnose(s.machine, s.data, o);
    effects = d.effects.size();
    revisited = revisits(d);
    benchmark::DoNotOptimize(effects);
  }
  state.counters["points"] = static_cast<double>(s.data.rows.size());
  state.counters["effects"] = static_cast<double>(effects);
  state.counters["revisited"] = static_cast<double>(revisited);
}
BENCHMARK(BM_DiagnoseGrid)
    ->Args({100000, 1, 0, 1, 1})
    ->Args({100000, 1, 0, 1, 0})
    ->Args({100000, 0, 0, 1, 1})
    ->Args({100000, 1, 1, 1, 1})
    ->Args({100000, 1, 1, 1, 0})
    ->Args({100000, 1, 1, 0, 1})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

// range(0): points; range(1): 1 with the swap test after the fit
// (rival_check.hpp), 0 without — its cost as a ratio in the same run;
// range(2): the hidden effects (make_setup); range(3): 1 with the backward
// check after the forward selection (backward_check.hpp), 0 without;
// range(4): 1 with a chosen cycle's period refined on the exact ΔRSS
// (SelectionOptions::exact_period), 0 with the periodogram's; range(5): 1
// with the revisit of the first step (SelectionOptions::revisit_paths), 0
// without; the counter `revisited` is the paths it ran; range(6): 1 with
// each chosen cycle's period refined once more in the final fit
// (SelectionOptions::refine_periods), 0 without; the counter `cycles` is
// the cyclic effects named.
void BM_Diagnose(benchmark::State& state) {
  const Setup s = make_setup(static_cast<int>(state.range(0)), static_cast<int>(state.range(2)));
  abbe::diagnose::DiagnoseOptions o;
  o.rivals.enabled = state.range(1) != 0;
  o.selection.backward_check = state.range(3) != 0;
  o.selection.exact_period = state.range(4) != 0;
  if (state.range(5) == 0) o.selection.revisit_paths = 0;
  o.selection.refine_periods = state.range(6) != 0;
  std::size_t effects = 0, revisited = 0, cycles = 0;
  for (auto _ : state) {
    const abbe::diagnose::Diagnosis d = abbe::diagnose::diagnose(s.machine, s.data, o);
    effects = d.effects.size();
    revisited = revisits(d);
    cycles = static_cast<std::size_t>(std::count_if(
        d.effects.begin(), d.effects.end(),
        [](const auto& e) { return e.term.kind == abbe::diagnose::TermKind::cyclic; }));
    benchmark::DoNotOptimize(effects);
  }
  state.counters["points"] = static_cast<double>(state.range(0));
  state.counters["effects"] = static_cast<double>(effects);
  state.counters["revisited"] = static_cast<double>(revisited);
  state.counters["cycles"] = static_cast<double>(cycles);
}
BENCHMARK(BM_Diagnose)
    ->Args({10000, 1, 0, 1, 1, 1, 1})
    ->Args({100000, 1, 0, 1, 1, 1, 1})
    ->Args({100000, 1, 0, 0, 1, 1, 1})
    ->Args({100000, 1, 0, 1, 0, 1, 1})
    ->Args({100000, 0, 0, 1, 1, 1, 1})
    ->Args({100000, 1, 1, 1, 1, 1, 1})
    ->Args({100000, 1, 1, 0, 1, 1, 1})
    ->Args({100000, 1, 1, 1, 0, 1, 1})
    ->Args({100000, 1, 0, 1, 1, 0, 1})
    ->Args({100000, 1, 1, 1, 1, 0, 1})
    ->Args({100000, 1, 2, 1, 1, 1, 1})
    ->Args({100000, 1, 2, 1, 1, 1, 0})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

}  // namespace
