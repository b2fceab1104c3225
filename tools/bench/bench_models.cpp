// Error-model throughput: point evaluations per second on one core for each
// model, along a fragmented toolpath (points 5 mm apart, as `abbe predict`
// evaluates them) and at random points (no segment locality).
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"

namespace {

using abbe::machine::Machine;
using abbe::model::ErrorModel;
using abbe::model::EvalPoint;
using abbe::model::ModelData;
using abbe::model::ModelKind;

// A machine like the test sample: every component of every axis measured
// every 25 mm, positioning bidirectional.
const Machine& bench_machine() {
  static const Machine machine = [] {
    std::string csv = "axis,component,position_mm,direction,value\n";
    const double lo[3] = {-1000, -600, -500};
    for (int a = 0; a < 3; ++a) {
      char axis = "XYZ"[a];
      for (int d = 0; d < 6; ++d) {
        char dir = "XYZABC"[d];
        for (const char* way :
             d == a ? std::vector<const char*>{"fwd", "rev"} : std::vector<const char*>{"mean"})
          for (double s = lo[a]; s <= 0.0; s += 25.0)
            csv += fmt::format("{},E{}{},{},{},{:.3f}\n", axis, dir, axis, s, way,
                               5.0 * std::sin(0.01 * s + d) + (way[0] == 'r' ? 1.0 : 0.0));
      }
    }
    abbe::machine::MachineSpec spec;
    spec.name = "bench";
    spec.chain = abbe::machine::KinematicChain::parse("w X' b Y Z t");
    spec.travel = {abbe::machine::Travel{-1000, 0}, abbe::machine::Travel{-600, 0},
                   abbe::machine::Travel{-500, 0}};
    spec.tool_length = 150.0;
    for (auto& rec : spec.axes) {
      rec.present = true;
      rec.measured_tip = {-500, -300, -300};
      rec.measured_tool_length = 150.0;
      rec.point = {Eigen::Vector3d(-800, -256, -478), Eigen::Vector3d(-500, -300, -320),
                   Eigen::Vector3d(-500, -300, -300)};
    }
    spec.squareness = {14.569, -24.362, 13.757};
    spec.table = abbe::machine::ComponentTable::parse(csv, "<bench>");
    return Machine(std::move(spec));
  }();
  return machine;
}

// A zig-zag pocket at 5 mm steps: neighbouring points share table segments.
std::vector<EvalPoint> path_points() {
  std::vector<EvalPoint> pts;
  for (int row = 0; row < 40; ++row) {
    double y = -550.0 + 13.0 * row;
    int sgn = row % 2 ? -1 : 1;
    for (int i = 0; i <= 180; ++i) {
      EvalPoint p;
      double x = sgn > 0 ? -950.0 + 5.0 * i : -50.0 - 5.0 * i;
      p.p = {x, y, -300.0 - 0.1 * row};
      p.tool_length = 150.0;
      p.dir = {static_cast<std::int8_t>(sgn), 1, 0};
      pts.push_back(p);
    }
  }
  return pts;
}

std::vector<EvalPoint> random_points() {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<EvalPoint> pts(8192);
  for (auto& p : pts) {
    p.p = {-1000.0 * u(rng), -600.0 * u(rng), -150.0 - 350.0 * u(rng)};
    p.tool_length = 150.0;
    p.dir = {1, -1, 0};
  }
  return pts;
}

// A random walk like the generated benchmark program: straight moves of
// 5–150 mm in random directions inside an 800 × 400 × 100 mm box, a point
// every 5 mm, every axis moving and reversing.
std::vector<EvalPoint> walk_points() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Eigen::Vector3d lo(-900.0, -500.0, -300.0), hi(-100.0, -100.0, -200.0);
  Eigen::Vector3d at(-500.0, -300.0, -250.0);
  std::vector<EvalPoint> pts;
  while (pts.size() < 65536) {
    Eigen::Vector3d to;
    for (int k = 0; k < 3; ++k) to[k] = lo[k] + (hi[k] - lo[k]) * u(rng);
    to = at + (to - at).normalized() * (5.0 + 145.0 * u(rng));
    to = to.cwiseMax(lo).cwiseMin(hi);
    const Eigen::Vector3d step = to - at;
    const int n = std::max(1, static_cast<int>(std::ceil(step.norm() / 5.0)));
    EvalPoint p;
    p.tool_length = 150.0;
    for (int k = 0; k < 3; ++k)
      p.dir[static_cast<std::size_t>(k)] = static_cast<std::int8_t>(step[k] > 0.0   ? 1
                                                                    : step[k] < 0.0 ? -1
                                                                                    : 0);
    for (int i = 1; i <= n; ++i) {
      p.p = at + step * (static_cast<double>(i) / n);
      pts.push_back(p);
    }
    at = to;
  }
  return pts;
}

void run(benchmark::State& state, ModelKind kind, const std::vector<EvalPoint>& pts) {
  ErrorModel model(bench_machine(), kind);
  ModelData data;
  std::size_t i = 0;
  for (auto _ : state) {
    auto d = model.evaluate(pts[i], data);
    benchmark::DoNotOptimize(d);
    if (++i == pts.size()) i = 0;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

void BM_AeArmPath(benchmark::State& s) { run(s, ModelKind::ae_arm, path_points()); }
void BM_HtmPath(benchmark::State& s) { run(s, ModelKind::htm, path_points()); }
void BM_DualPath(benchmark::State& s) { run(s, ModelKind::dual, path_points()); }
void BM_AeArmWalk(benchmark::State& s) { run(s, ModelKind::ae_arm, walk_points()); }
void BM_AeArmRandom(benchmark::State& s) { run(s, ModelKind::ae_arm, random_points()); }
void BM_DualRandom(benchmark::State& s) { run(s, ModelKind::dual, random_points()); }

BENCHMARK(BM_AeArmPath);
BENCHMARK(BM_HtmPath);
BENCHMARK(BM_DualPath);
BENCHMARK(BM_AeArmWalk);
BENCHMARK(BM_AeArmRandom);
BENCHMARK(BM_DualRandom);

}  // namespace
