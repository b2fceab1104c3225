// Throughput of the front end on an in-memory generated program (gen_program's
// generator, 100 k blocks): read + parse, parse_line alone, parse + interpret,
// + fragment (5 mm), + CSV formatting. Items are program lines.
#include <benchmark/benchmark.h>

#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "abbe/gcode/parser.hpp"
#include "abbe/gcode/program.hpp"
#include "abbe/pipeline/path_writer.hpp"
#include "abbe/pipeline/program_path.hpp"
#include "tools/gen/program_generator.hpp"

namespace {

constexpr std::size_t kBlocks = 100000;

const std::string& program() {
  static const std::string text = [] {
    std::string s;
    fmt::memory_buffer buffer;
    abbe::gen::ProgramGenerator generator(42);
    generator.write(kBlocks, buffer,
                    [&](const fmt::memory_buffer& b) { s.append(b.data(), b.size()); });
    return s;
  }();
  return text;
}

void report(benchmark::State& state, std::size_t lines) {
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(lines));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(program().size()));
}

void BM_Parse(benchmark::State& state) {
  std::size_t lines = 0;
  for (auto _ : state) {
    std::istringstream in(program());
    abbe::gcode::BlockReader reader(in, "<bench>");
    abbe::gcode::Block block;
    lines = 0;
    while (reader.next(block)) ++lines;
    benchmark::DoNotOptimize(block);
  }
  report(state, lines);
}
BENCHMARK(BM_Parse)->Unit(benchmark::kMillisecond);

// parse_line on each line of the program, without the reader: what the
// grammar and its actions cost alone.
void BM_ParseLines(benchmark::State& state) {
  const std::string& text = program();
  std::vector<std::string_view> lines;
  for (std::size_t at = 0; at < text.size();) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    lines.emplace_back(text.data() + at, end - at);
    at = end + 1;
  }
  const std::string file = "<bench>";
  abbe::gcode::Block block;
  for (auto _ : state) {
    std::size_t n = 0;
    for (const auto line : lines) abbe::gcode::parse_line(line, ++n, file, block);
    benchmark::DoNotOptimize(block);
  }
  report(state, lines.size());
}
BENCHMARK(BM_ParseLines)->Unit(benchmark::kMillisecond);

void BM_Interpret(benchmark::State& state) {
  std::size_t lines = 0;
  for (auto _ : state) {
    std::istringstream in(program());
    double sum = 0.0;
    const auto stats = abbe::gcode::run_program(
        in, "<bench>", {}, [&](const abbe::gcode::Motion& m) { sum += m.end.x(); });
    benchmark::DoNotOptimize(sum);
    lines = stats.lines;
  }
  report(state, lines);
}
BENCHMARK(BM_Interpret)->Unit(benchmark::kMillisecond);

void BM_InterpretFragment(benchmark::State& state) {
  std::size_t lines = 0, points = 0;
  for (auto _ : state) {
    std::istringstream in(program());
    points = 0;
    const auto run = abbe::pipeline::run_path(in, "<bench>", {}, {},
                                              [&](const abbe::path::PathPoint&) { ++points; });
    lines = run.program.lines;
  }
  report(state, lines);
  state.counters["points"] = static_cast<double>(points);
}
BENCHMARK(BM_InterpretFragment)->Unit(benchmark::kMillisecond);

void BM_InterpretFragmentCsv(benchmark::State& state) {
  std::size_t lines = 0, bytes = 0;
  for (auto _ : state) {
    std::istringstream in(program());
    bytes = 0;
    abbe::pipeline::PathWriter writer(abbe::pipeline::PathFormat::csv,
                                      [&](const char*, std::size_t n) { bytes += n; });
    const auto run = abbe::pipeline::run_path(
        in, "<bench>", {}, {}, [&](const abbe::path::PathPoint& p) { writer.write(p); });
    writer.finish();
    lines = run.program.lines;
  }
  report(state, lines);
  state.counters["csv_bytes"] = static_cast<double>(bytes);
}
BENCHMARK(BM_InterpretFragmentCsv)->Unit(benchmark::kMillisecond);

}  // namespace
