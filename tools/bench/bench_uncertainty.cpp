// Speed of `abbe predict --uncertainty N` against plain `abbe predict` in the
// same run (docs/performance.md, "Uncertainty of the prediction"): the
// thesis toolpaths (nc-samples/thesis-toolpath-{1,2}.ngc) on the sample
// machine with every source of uncertainty stated
// (machines/sample/machine-uncertainty.yaml), one model (ae-arm) or all
// three; plain predict, N = 200 Monte Carlo draws, and 200 draws with the
// part set up again in every draw (--align best-fit). The library calls of
// the CLI, without process start-up, machine loading and output.
// Arguments: toolpath (1, 2), models (1: ae-arm, 3: all), draws.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "abbe/machine/machine.hpp"
#include "abbe/model/model_kind.hpp"
#include "abbe/pipeline/aligned_prediction.hpp"
#include "abbe/pipeline/predict.hpp"
#include "abbe/pipeline/prediction_uncertainty.hpp"

namespace {

const abbe::machine::Machine& uncertain_machine() {
  static const abbe::machine::Machine machine = abbe::machine::Machine::load(
      std::string(ABBE_SOURCE_DIR) + "/machines/sample/machine-uncertainty.yaml");
  return machine;
}

std::string toolpath(std::int64_t n) {
  const std::string file =
      std::string(ABBE_SOURCE_DIR) + "/nc-samples/thesis-toolpath-" + std::to_string(n) + ".ngc";
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

abbe::pipeline::PredictOptions options(std::int64_t models) {
  abbe::pipeline::PredictOptions po;
  po.models = models == 3 ? abbe::model::parse_model_list("all")
                          : std::vector<abbe::model::ModelKind>{abbe::model::ModelKind::ae_arm};
  return po;
}

void label(benchmark::State& state, std::size_t points) {
  state.SetLabel("thesis-toolpath-" + std::to_string(state.range(0)) +
                 (state.range(1) == 3 ? ", all models" : ", ae-arm"));
  state.counters["points"] = static_cast<double>(points);
}

void BM_PredictPlain(benchmark::State& state) {
  const std::string program = toolpath(state.range(0));
  const auto po = options(state.range(1));
  std::size_t points = 0;
  for (auto _ : state) {
    std::istringstream in(program);
    const auto summary = abbe::pipeline::predict(in, "thesis.ngc", uncertain_machine(), po,
                                                 [](const auto&, std::size_t, const auto&) {});
    points = summary.points;
    benchmark::DoNotOptimize(points);
  }
  label(state, points);
}

void BM_PredictUncertainty(benchmark::State& state) {
  const std::string program = toolpath(state.range(0));
  const auto po = options(state.range(1));
  abbe::pipeline::UncertaintyOptions uo;
  uo.draws = static_cast<std::size_t>(state.range(2));
  std::size_t points = 0;
  for (auto _ : state) {
    std::istringstream in(program);
    points = 0;
    const auto p = abbe::pipeline::predict_with_uncertainty(
        in, "thesis.ngc", uncertain_machine(), po, uo, {},
        [&](const abbe::model::EvalPoint&, std::size_t, const std::vector<abbe::model::Deviation>&,
            const std::vector<double>&, const std::vector<Eigen::Vector3d>&) { ++points; });
    benchmark::DoNotOptimize(p.uncertainty.models.front().all.figures[4].u);
  }
  label(state, points);
}

void BM_PredictUncertaintyAligned(benchmark::State& state) {
  const std::string program = toolpath(state.range(0));
  const auto po = options(state.range(1));
  abbe::pipeline::UncertaintyOptions uo;
  uo.draws = static_cast<std::size_t>(state.range(2));
  abbe::pipeline::AlignOptions ao;
  ao.method = abbe::pipeline::AlignMethod::best_fit;
  std::size_t points = 0;
  for (auto _ : state) {
    std::istringstream in(program);
    points = 0;
    const auto p = abbe::pipeline::predict_with_uncertainty(
        in, "thesis.ngc", uncertain_machine(), po, uo, ao, {},
        [&](const abbe::model::EvalPoint&, std::size_t, const std::vector<abbe::model::Deviation>&,
            const std::vector<double>&, const std::vector<Eigen::Vector3d>&,
            const std::vector<Eigen::Vector3d>&,
            const std::vector<Eigen::Vector3d>&) { ++points; });
    benchmark::DoNotOptimize(p.uncertainty.models.front().aligned.figures[4].u);
  }
  label(state, points);
}

void toolpaths(benchmark::internal::Benchmark* b, std::int64_t draws) {
  for (std::int64_t t : {1, 2})
    for (std::int64_t m : {1, 3}) b->Args({t, m, draws});
  b->ArgNames({"toolpath", "models", "draws"});
}

BENCHMARK(BM_PredictPlain)
    ->Apply([](benchmark::internal::Benchmark* b) { toolpaths(b, 0); })
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PredictUncertainty)
    ->Apply([](benchmark::internal::Benchmark* b) { toolpaths(b, 200); })
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PredictUncertaintyAligned)
    ->Apply([](benchmark::internal::Benchmark* b) { toolpaths(b, 200); })
    ->Unit(benchmark::kMillisecond);

}  // namespace
