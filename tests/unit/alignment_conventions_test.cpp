// The free constants of real laser conventions (docs/models.md, "Reference
// conventions and the part"): a component table that differs from another
// only by what a convention leaves free — linear positioning zeroed at a
// reference target, a straightness slope removed together with the
// squareness measured against the same reference line, angles relative to a
// reference position together with the squareness they go with — gives the
// same prediction of the part after a best fit, in every model.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>

#include "abbe/model/error_model.hpp"
#include "abbe/model/model_kind.hpp"
#include "abbe/pipeline/part_alignment.hpp"
#include "model_test_machines.hpp"

namespace abbe {
namespace {

using Eigen::Vector3d;

// Value added to a component at position s: a + b·s (µm or µrad; b per mm).
struct Offset {
  double a = 0.0, b = 0.0;
};
using Offsets = std::map<std::string, Offset>;

// A random table (every component, 7 knots) plus the offsets, squareness
// `sq` (µrad) and random reflector records (the same for every seed).
machine::Machine machine_with(unsigned seed, const Offsets& add, const machine::Squareness& sq) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::string csv = test::kHeader;
  for (char ax : {'X', 'Y', 'Z'})
    for (char d : {'X', 'Y', 'Z', 'A', 'B', 'C'}) {
      const bool ang = d == 'A' || d == 'B' || d == 'C';
      const std::string name = fmt::format("E{}{}", d, ax);
      const auto it = add.find(name);
      const Offset o = it == add.end() ? Offset{} : it->second;
      for (int i = 0; i <= 6; ++i) {
        const double s = -1200.0 + 400.0 * i;
        const double v = (ang ? 20.0 : 5.0) * u(rng) + o.a + o.b * s;
        csv += fmt::format("{},{},{},mean,{:.17g}\n", ax, name, s, v);
      }
    }
  machine::MachineSpec spec = test::spec_with("w X' b Y Z t", csv);
  test::randomize_records(spec, rng);
  spec.squareness = sq;
  spec.tool_length = 130.0;
  return machine::Machine(spec);
}

// A part: cutting points on a block's faces and a pocket, one tool.
std::vector<model::EvalPoint> part_points() {
  std::vector<model::EvalPoint> pts;
  auto add = [&](double x, double y, double z) {
    model::EvalPoint p;
    p.p = {x, y, z};
    p.tool_length = 130.0;
    pts.push_back(p);
  };
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 10; ++j) add(-700.0 + 20.0 * i, -400.0 + 30.0 * j, -200.0);
  for (int i = 0; i <= 20; ++i)
    for (int k = 1; k <= 5; ++k) {
      add(-700.0 + 20.0 * i, -400.0, -200.0 - 25.0 * k);
      add(-700.0 + 20.0 * i, -100.0, -200.0 - 25.0 * k);
    }
  for (int i = 0; i <= 40; ++i) add(-600.0 + 5.0 * i, -250.0 + 40.0 * std::sin(0.2 * i), -260.0);
  return pts;
}

// The aligned deviations (µm) of every part point, best fit, one model.
std::vector<Vector3d> aligned(const machine::Machine& m, model::ModelKind kind) {
  const model::ErrorModel model(m, kind);
  model::ModelData data;
  pipeline::PartPoints part;
  for (const model::EvalPoint& p : part_points()) part.add(p.p, model.evaluate(p, data).e_um);
  const pipeline::RigidMotion fit = pipeline::best_fit(part);
  std::vector<Vector3d> out;
  for (std::size_t i = 0; i < part.size(); ++i)
    out.push_back(pipeline::aligned_deviation_um(fit, part.nominal_mm[i], part.deviation_um[i]));
  return out;
}

struct Case {
  const char* what;
  Offsets add;
  machine::Squareness sq_change;  // µrad
};

const machine::Squareness kSquareness{14.569, -24.362, 13.757};

machine::Squareness plus(const machine::Squareness& a, const machine::Squareness& b) {
  return {a.ec0y + b.ec0y, a.eb0z + b.eb0z, a.ea0z + b.ea0z};
}

// Tolerance: the alignment is an exact rigid motion, so it also turns the
// deviations: R·e differs from e by ω × e, a product of two small terms
// (a few µrad × a few µm, ~1e-4 µm here, measured up to 7e-5 µm); htm and
// dual carry their own products of small terms as well.
double tolerance(model::ModelKind kind) { return kind == model::ModelKind::dual ? 2e-3 : 5e-4; }

void expect_same_aligned(const Case& c) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const machine::Machine base = machine_with(seed, {}, kSquareness);
    const machine::Machine conv = machine_with(seed, c.add, plus(kSquareness, c.sq_change));
    for (model::ModelKind kind :
         {model::ModelKind::htm, model::ModelKind::ae_arm, model::ModelKind::dual}) {
      const std::vector<Vector3d> r0 = aligned(base, kind);
      const std::vector<Vector3d> r1 = aligned(conv, kind);
      double worst = 0, size = 0;
      for (std::size_t i = 0; i < r0.size(); ++i) {
        worst = std::max(worst, (r1[i] - r0[i]).norm());
        size = std::max(size, r0[i].norm());
      }
      EXPECT_LT(worst, tolerance(kind)) << c.what << ", " << model::to_string(kind);
      EXPECT_GT(size, 1.0) << "the aligned prediction is not trivially zero";
    }
  }
}

// The same offsets without the squareness that goes with them do change the
// aligned prediction (so the test above can fail).
void expect_different_without_squareness(const Case& c) {
  const machine::Machine base = machine_with(1, {}, kSquareness);
  const machine::Machine conv = machine_with(1, c.add, kSquareness);
  const std::vector<Vector3d> r0 = aligned(base, model::ModelKind::ae_arm);
  const std::vector<Vector3d> r1 = aligned(conv, model::ModelKind::ae_arm);
  double worst = 0;
  for (std::size_t i = 0; i < r0.size(); ++i) worst = std::max(worst, (r1[i] - r0[i]).norm());
  EXPECT_GT(worst, 0.1) << c.what;
}

TEST(AlignmentConventions, LinearPositioningZeroedAtAReferenceTarget) {
  expect_same_aligned(
      {"EXX, EYY, EZZ zeroed", {{"EXX", {-3.7, 0}}, {"EYY", {2.1, 0}}, {"EZZ", {5.0, 0}}}, {}});
}

TEST(AlignmentConventions, StraightnessConstantRemoved) {
  expect_same_aligned({"straightness constants",
                       {{"EYX", {1.3, 0}},
                        {"EZX", {-2.0, 0}},
                        {"EXY", {0.7, 0}},
                        {"EZY", {-1.1, 0}},
                        {"EXZ", {2.4, 0}},
                        {"EYZ", {-0.6, 0}}},
                       {}});
}

// Slope κ (µm/mm) removed from a straightness; the squareness measured against
// the same reference line changes by ±1000·κ µrad (docs/models.md).
TEST(AlignmentConventions, StraightnessSlopeRemovedWithItsSquareness) {
  const double k = 0.004;  // µm/mm = 4 µrad
  const Case cases[] = {
      {"EYX slope + EC0Y", {{"EYX", {0, k}}}, {1000 * k, 0, 0}},
      {"EXY slope + EC0Y", {{"EXY", {0, k}}}, {1000 * k, 0, 0}},
      {"EZX slope + EB0Z", {{"EZX", {0, k}}}, {0, -1000 * k, 0}},
      {"EXZ slope + EB0Z", {{"EXZ", {0, k}}}, {0, -1000 * k, 0}},
      {"EZY slope + EA0Z", {{"EZY", {0, k}}}, {0, 0, 1000 * k}},
      {"EYZ slope + EA0Z", {{"EYZ", {0, k}}}, {0, 0, 1000 * k}},
  };
  for (const Case& c : cases) {
    expect_same_aligned(c);
    expect_different_without_squareness(c);
  }
}

// Angles relative to a reference position: a constant per angular component.
// Table axis X and the Z ram (and ECY): a rigid motion of the part. EAY and
// EBY tilt the Z axis that Y carries: absorbed by EA0Z, EB0Z.
TEST(AlignmentConventions, RelativeAnglesWithTheirSquareness) {
  expect_same_aligned({"EAX, EBX, ECX, ECY, EAZ, EBZ, ECZ constants",
                       {{"EAX", {12, 0}},
                        {"EBX", {-8, 0}},
                        {"ECX", {5, 0}},
                        {"ECY", {-9, 0}},
                        {"EAZ", {7, 0}},
                        {"EBZ", {-4, 0}},
                        {"ECZ", {11, 0}}},
                       {}});
  const Case eay{"EAY constant + EA0Z", {{"EAY", {10, 0}}}, {0, 0, -10}};
  const Case eby{"EBY constant + EB0Z", {{"EBY", {-6, 0}}}, {0, 6, 0}};
  expect_same_aligned(eay);
  expect_same_aligned(eby);
  expect_different_without_squareness(eay);
  expect_different_without_squareness(eby);
}

}  // namespace
}  // namespace abbe
