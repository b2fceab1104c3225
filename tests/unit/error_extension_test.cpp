// ErrorModel::with_extension and the overlay adapter: the extension's terms
// are added to every model's prediction and nothing else changes; the
// overlay is evaluated as when it was fitted (ContextBuilder); compensation
// with the extended model moves each commanded point by minus the extra term.
#include "abbe/model/error_extension.hpp"

#include <gtest/gtest.h>

#include <regex>
#include <sstream>

#include "abbe/compensate/point_solver.hpp"
#include "abbe/compensate/program_compensator.hpp"
#include "abbe/diagnose/context.hpp"
#include "abbe/diagnose/overlay_extension.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/pipeline/interpreter_setup.hpp"

namespace abbe {
namespace {

const std::string kSample = std::string(ABBE_SOURCE_DIR) + "/machines/sample/machine.yaml";
const std::string kZero = std::string(ABBE_TEST_DATA_DIR) + "/compensate/zero.yaml";
constexpr model::ModelKind kKinds[] = {model::ModelKind::htm, model::ModelKind::ae_arm,
                                       model::ModelKind::dual};

class ConstantExtension : public model::ErrorExtension {
 public:
  explicit ConstantExtension(Eigen::Vector3d k) : k_(std::move(k)) {}
  Eigen::Vector3d extra_um(const model::EvalPoint&, const model::Deviation&,
                           const model::ModelData&) const override {
    return k_;
  }

 private:
  Eigen::Vector3d k_;
};

std::vector<model::EvalPoint> some_points() {
  std::vector<model::EvalPoint> out;
  for (double x : {-880.0, -410.0, -60.0})
    for (double y : {-420.0, -95.0})
      for (double z : {-350.0, -120.0}) {
        model::EvalPoint p;
        p.p = Eigen::Vector3d(x, y, z);
        p.tool_length = 200.0;
        p.dir = {1, -1, static_cast<std::int8_t>(z < -200.0 ? 1 : 0)};
        p.time = 100.0;
        out.push_back(p);
      }
  return out;
}

TEST(ErrorExtension, AddsItsTermsAndLeavesThePlainModel) {
  const machine::Machine m = machine::Machine::load(kSample);
  const Eigen::Vector3d k(1.5, -2.0, 0.25);
  for (auto kind : kKinds) {
    const model::ErrorModel plain(m, kind);
    const model::ErrorModel extended =
        plain.with_extension(std::make_shared<const ConstantExtension>(k));
    EXPECT_EQ(plain.extension(), nullptr);
    ASSERT_NE(extended.extension(), nullptr);
    EXPECT_EQ(extended.with_extension(nullptr).extension(), nullptr);
    const model::ErrorModel fresh(m, kind);
    model::ModelData d1, d2, d3;
    for (const auto& p : some_points()) {
      const model::Deviation a = plain.evaluate(p, d1);
      const model::Deviation b = extended.evaluate(p, d2);
      const model::Deviation c = fresh.evaluate(p, d3);
      EXPECT_EQ(a.e_um, c.e_um);  // unchanged, bit for bit
      EXPECT_GT(a.e_um.norm(), 1.0);
      EXPECT_NEAR((b.e_um - a.e_um - k).norm(), 0.0, 1e-12);
      EXPECT_EQ(b.second_order_um, a.second_order_um);
    }
  }
}

// scale X→X 10 ppm: 1e-3·10·s_x µm along X; reversal Y→Y 4 µm: ±2 µm along Y.
const char* kLinearOverlay = R"(format: abbe-overlay-1
model: ae-arm
effects:
  - term: scale
    axis: X
    direction: X
    coef: [10]
  - term: reversal
    axis: Y
    direction: Y
    coef: [4]
)";

TEST(ErrorExtension, OverlayWithKnownTerms) {
  const machine::Machine m = machine::Machine::load(kSample);
  const auto ext = std::make_shared<const diagnose::OverlayExtension>(
      diagnose::Overlay::parse(kLinearOverlay, "<overlay>"), m);
  for (auto kind : kKinds) {
    const model::ErrorModel plain(m, kind);
    const model::ErrorModel extended = plain.with_extension(ext);
    model::ModelData d1, d2;
    for (const auto& p : some_points()) {
      const Eigen::Vector3d extra = extended.evaluate(p, d2).e_um - plain.evaluate(p, d1).e_um;
      EXPECT_NEAR(extra.x(), 1e-2 * p.p.x(), 1e-12);
      EXPECT_NEAR(extra.y(), 2.0 * p.dir[1], 1e-12);
      EXPECT_NEAR(extra.z(), 0.0, 1e-12);
    }
  }
}

// Terms that need the base model's context (ε_j, the htm − ae-arm
// difference) give what they gave when diagnose fitted them.
TEST(ErrorExtension, OverlayMatchesTheDiagnosisContext) {
  const machine::Machine m = machine::Machine::load(kSample);
  const char* yaml = R"(format: abbe-overlay-1
model: ae-arm
effects:
  - term: model_choice
    other_model: htm
    coef: [0.3]
  - term: arm_offset
    axis: Y
    direction: Z
    coef: [40]
  - term: thermal_drift
    axis: X
    direction: X
    tau_s: 0
    coef: [1.5]
)";
  const diagnose::Overlay ov = diagnose::Overlay::parse(yaml, "<overlay>");
  const auto ext = std::make_shared<const diagnose::OverlayExtension>(ov, m);
  const model::ErrorModel plain(m, model::ModelKind::ae_arm);
  const model::ErrorModel extended = plain.with_extension(ext);
  diagnose::ContextBuilder cb(m, model::ModelKind::ae_arm);
  model::ModelData d1, d2;
  for (const auto& p : some_points()) {
    Eigen::Vector3d base;
    const Eigen::Vector3d want = ov.evaluate(cb.make(p, "", base));
    const Eigen::Vector3d got = extended.evaluate(p, d2).e_um - plain.evaluate(p, d1).e_um;
    EXPECT_GT(want.norm(), 0.1);
    EXPECT_NEAR((got - want).norm(), 0.0, 1e-9);
  }
}

// Time-dependent terms: at the point's time by default, at one campaign
// time with fixed_time_s (compensate and verify).
TEST(ErrorExtension, TimeDependentTermsAtTheFixedTime) {
  const machine::Machine m = machine::Machine::load(kZero);
  // thermal_drift X→X, τ = 0: coef·t/3600 µm (µm per hour).
  const auto ov = diagnose::Overlay::parse(R"(format: abbe-overlay-1
model: ae-arm
effects:
  - {term: thermal_drift, axis: X, direction: X, tau_s: 0, coef: [6]}
)",
                                           "<overlay>");
  const diagnose::OverlayExtension along(ov, m), fixed(ov, m, 1800.0);
  EXPECT_TRUE(along.time_dependent());
  EXPECT_FALSE(diagnose::OverlayExtension(diagnose::Overlay::parse(kLinearOverlay, "<o>"), m)
                   .time_dependent());
  const model::ErrorModel plain(m, model::ModelKind::ae_arm);
  model::ModelData data;
  for (double t : {0.0, 600.0, 7200.0}) {
    model::EvalPoint p;
    p.p = Eigen::Vector3d(-400.0, -200.0, -300.0);
    p.time = t;
    const model::Deviation d = plain.evaluate(p, data);
    EXPECT_NEAR(along.extra_um(p, d, data).x(), 6.0 * t / 3600.0, 1e-12);
    EXPECT_NEAR(fixed.extra_um(p, d, data).x(), 3.0, 1e-12);
  }
}

TEST(ErrorExtension, CompensatedPointMovesByMinusTheTerm) {
  const auto ov = diagnose::Overlay::parse(kLinearOverlay, "<overlay>");
  // All-zero tables: the extension is the whole error, c = n − extra exactly.
  {
    const machine::Machine m = machine::Machine::load(kZero);
    const model::ErrorModel em =
        model::ErrorModel(m, model::ModelKind::ae_arm)
            .with_extension(std::make_shared<diagnose::OverlayExtension>(ov, m));
    const compensate::PointSolver solver(em);
    model::ModelData data;
    for (const auto& n : some_points()) {
      const compensate::Solution s = solver.solve(n, data);
      ASSERT_TRUE(s.converged);
      // c_x = n_x − 1e-5·c_x (the term is taken at c): c_x = n_x / (1 + 1e-5), to the
      // solver tolerance (0.01 µm).
      EXPECT_NEAR(s.c.x(), n.p.x() / (1.0 + 1e-5), 1e-5);
      EXPECT_NEAR(s.c.y(), n.p.y() - 2e-3 * n.dir[1], 1e-12);
      EXPECT_EQ(s.c.z(), n.p.z());
    }
  }
  // The sample machine: the extended solution differs from the plain one by
  // minus the term (to the solver tolerance and the field's µm/m gradient).
  {
    const machine::Machine m = machine::Machine::load(kSample);
    const model::ErrorModel plain(m, model::ModelKind::ae_arm);
    const model::ErrorModel extended =
        plain.with_extension(std::make_shared<diagnose::OverlayExtension>(ov, m));
    const compensate::PointSolver sp(plain), se(extended);
    model::ModelData d1, d2;
    for (const auto& n : some_points()) {
      const compensate::Solution a = sp.solve(n, d1), b = se.solve(n, d2);
      ASSERT_TRUE(a.converged && b.converged);
      const Eigen::Vector3d term(1e-2 * n.p.x(), 2.0 * n.dir[1], 0.0);  // µm
      EXPECT_LT((1e3 * (b.c - a.c) + term).norm(), 0.05);
    }
  }
}

// compensate_program with the extended model on the all-zero machine: every
// written coordinate moves by minus the overlay's term.
TEST(ErrorExtension, CompensatedProgramMovesByMinusTheTerm) {
  const machine::Machine m = machine::Machine::load(kZero);
  // reversal terms: 0.5·coef·dir; every motion below runs in −X, −Y, −Z.
  const char* yaml = R"(format: abbe-overlay-1
model: ae-arm
effects:
  - {term: reversal, axis: X, direction: X, coef: [-4]}
  - {term: reversal, axis: Y, direction: Y, coef: [2]}
  - {term: reversal, axis: Z, direction: Z, coef: [-1]}
)";
  const model::ErrorModel em = model::ErrorModel(m, model::ModelKind::ae_arm)
                                   .with_extension(std::make_shared<diagnose::OverlayExtension>(
                                       diagnose::Overlay::parse(yaml, "<overlay>"), m));
  // extra = (+2, −1, +0.5) µm → c = n + (−0.002, +0.001, −0.0005) mm.
  std::istringstream in("G21 G90 G17\nG0 X-100 Y-100 Z-100\nG1 X-103 Y-101 Z-101 F500\nM2\n");
  std::string out;
  compensate::compensate_program(in, "t.nc", pipeline::interpreter_config(m), em, {},
                                 [&](const char* d, std::size_t n) { out.append(d, n); });
  const std::regex word("([XYZ])(-?[0-9.]+)");
  std::vector<double> values;
  std::istringstream lines(out);
  std::string line;
  int motion_lines = 0;
  while (std::getline(lines, line)) {
    if (line.rfind("G0", 0) != 0 && line.rfind("G1", 0) != 0) continue;
    ++motion_lines;
    for (std::sregex_iterator it(line.begin(), line.end(), word), end; it != end; ++it)
      values.push_back(std::stod((*it)[2]));
  }
  ASSERT_EQ(motion_lines, 2) << out;
  ASSERT_EQ(values.size(), 6u) << out;
  const double want[6] = {-100.002, -99.999, -100.0005, -103.002, -100.999, -101.0005};
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(values[static_cast<std::size_t>(i)], want[i], 0.6e-4);
}

}  // namespace
}  // namespace abbe
