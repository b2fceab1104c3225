// --min-segment: no piece abbe inserts is shorter than the minimum; reversal
// jumps below it are taken up along the move when they are within tol (or
// always, with spread_takeups), and keep their micro move otherwise.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <sstream>

#include "abbe/compensate/motion_path.hpp"
#include "abbe/compensate/path_verifier.hpp"
#include "abbe/compensate/program_compensator.hpp"
#include "abbe/gcode/program.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"
#include "tools/gen/program_generator.hpp"

namespace abbe::compensate {
namespace {

const std::string kSample = std::string(ABBE_SOURCE_DIR) + "/machines/sample/machine.yaml";

struct Compensated {
  std::string text;
  CompensateSummary summary;
};

Compensated compensate(const std::string& program, const CompensateOptions& o) {
  const machine::Machine m = machine::Machine::load(kSample);
  const model::ErrorModel em(m, model::ModelKind::ae_arm);
  std::istringstream in(program);
  Compensated r;
  r.summary = compensate_program(in, "p", pipeline::interpreter_config(m), em, o,
                                 [&](const char* d, std::size_t n) { r.text.append(d, n); });
  return r;
}

VerifyStats verify(const std::string& compensated, const std::string& original, double tol_um) {
  const machine::Machine m = machine::Machine::load(kSample);
  const model::ErrorModel em(m, model::ModelKind::ae_arm);
  std::istringstream c(compensated), o(original);
  VerifyOptions vo;
  vo.tol_um = tol_um;
  return verify_program(c, "out", o, "in", pipeline::interpreter_config(m), em, vo);
}

// verify passes the compensated program at tol, every point matched.
void expect_verified(const std::string& compensated, const std::string& original, double tol_um) {
  const VerifyStats v = verify(compensated, original, tol_um);
  EXPECT_LE(v.max_um, tol_um);
  EXPECT_LE(v.backward_max_um, tol_um);
  EXPECT_EQ(v.unmatched + v.backward_unmatched, 0u);
}

// Lengths (mm, along the curve) of the feed motions of a program.
std::vector<double> feed_lengths(const std::string& text) {
  const machine::Machine m = machine::Machine::load(kSample);
  std::istringstream s(text);
  std::vector<double> out;
  gcode::run_program(s, "p", pipeline::interpreter_config(m), [&](const gcode::Motion& x) {
    if (x.kind == gcode::MotionKind::linear || x.kind == gcode::MotionKind::arc)
      out.push_back(MotionPath(x).length());
  });
  return out;
}

std::string generated(int blocks, unsigned seed) {
  gen::ProgramGenerator g(seed);
  fmt::memory_buffer buf;
  std::string program;
  g.write(blocks, buf, [&](fmt::memory_buffer& b) {
    program.append(b.data(), b.size());
    b.clear();
  });
  return program;
}

// The default options with one field set.
template <class T>
CompensateOptions options_with(T CompensateOptions::*field, T value) {
  CompensateOptions o;
  o.*field = value;
  return o;
}

// How many feed motions of a program are shorter than `mm` (to 1e-9 mm).
std::size_t feed_moves_shorter_than(const std::string& text, double mm) {
  std::size_t n = 0;
  for (double l : feed_lengths(text))
    if (l < mm - 1e-9) ++n;
  return n;
}

double shortest(const std::vector<double>& v) {
  double s = 1e300;
  for (double x : v) s = std::min(s, x);
  return s;
}

// The sample machine's reversal jumps are 1–16 µm: with tol 1 µm and the
// default 0.01 mm, those within tol are taken up along the move and the
// larger ones keep their micro move (reported as shorter than the minimum).
TEST(CompensateMinSegment, EveryReversalIsTakenOnceWhicheverWay) {
  const std::string program = generated(1500, 5);
  const Compensated micro = compensate(program, options_with(&CompensateOptions::min_segment, 0.0));
  ASSERT_GT(micro.summary.takeup_moves, 100u);
  EXPECT_EQ(micro.summary.takeups_spread, 0u);

  const Compensated s = compensate(program, options_with(&CompensateOptions::spread_takeups, true));
  // The same reversals, each either spread or given a micro move.
  EXPECT_EQ(s.summary.takeups_spread + s.summary.takeup_moves, micro.summary.takeup_moves);
  EXPECT_GT(s.summary.takeups_spread, 0u);
  EXPECT_LE(s.summary.max_takeup_um, 10.0);
  EXPECT_EQ(s.summary.short_takeup_moves, 0u);
  // No move of the output is shorter than the minimum (the program's own
  // moves are all longer than it).
  ASSERT_GT(shortest(feed_lengths(program)), 0.01);
  EXPECT_GE(shortest(feed_lengths(s.text)), 0.01 - 1e-9);
  EXPECT_GE(s.summary.shortest_inserted_mm, 0.01);
  // Exact micro moves: many far below the minimum.
  EXPECT_LT(shortest(feed_lengths(micro.text)), 0.005);

  // The default: micro moves only for jumps beyond tol; verify passes.
  const Compensated d = compensate(program, CompensateOptions{});
  EXPECT_EQ(d.summary.takeups_spread + d.summary.takeup_moves, micro.summary.takeup_moves);
  EXPECT_LE(d.summary.max_takeup_um, 1.0);
  expect_verified(d.text, program, 1.0);
}

// With tol 20 µm every jump of the sample machine is within tol: those
// below the minimum are taken up along the move, the larger ones (Z's
// 15.5 µm) keep a micro move that is longer than the minimum; no output
// move is shorter than the minimum, and verify still passes at that tol.
TEST(CompensateMinSegment, JumpsWithinTolNeedNoMicroMove) {
  const std::string program = generated(800, 9);
  const Compensated r = compensate(program, options_with(&CompensateOptions::tol_um, 20.0));
  EXPECT_GT(r.summary.takeups_spread, 0u);
  EXPECT_EQ(r.summary.short_takeup_moves, 0u);
  EXPECT_GE(shortest(feed_lengths(r.text)), 0.01 - 1e-9);
  expect_verified(r.text, program, 20.0);
}

// A larger minimum merges pieces; it never makes the result worse than tol
// where merging is possible, and the count of kept short pieces says where
// it was not.
TEST(CompensateMinSegment, LargerMinimumStillWithinTol) {
  const std::string program = generated(800, 13);
  const Compensated r = compensate(program, options_with(&CompensateOptions::min_segment, 0.2));
  expect_verified(r.text, program, 1.0);
  EXPECT_GE(r.summary.min_segment_mm, 0.2);
  // Every piece shorter than 0.2 mm is accounted for: a kept piece or a take-up move.
  const std::size_t short_moves = feed_moves_shorter_than(r.text, 0.2);
  const std::size_t short_in = feed_moves_shorter_than(program, 0.2);
  EXPECT_LE(short_moves, short_in + r.summary.short_takeup_moves + r.summary.short_pieces_kept +
                             r.summary.takeup_moves);
}

}  // namespace
}  // namespace abbe::compensate
