// AlignmentExtension and program_setup (compensate --align): the extended
// model predicts exactly the deviation left after the part's set-up, and a
// machine with rigid-body-only errors leaves nothing to correct, with a best
// fit or with datums (compensate --align datums: the set-up of predict
// --align datums).
#include "abbe/pipeline/alignment_extension.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <sstream>

#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"
#include "align_test_options.hpp"

namespace abbe {
namespace {

// A rectangle at z = −280 and its plunge (thesis toolpath 1's shape), tool 1
// (200 mm in the machine's tool table) with G43, so program Z is the tip.
const char* kProgram =
    "G17 G21 G90 G94\nT1 M6\nG43 H1\nG0 X-350 Y-150\nG0 Z-270\nG1 Z-280 F300\nG1 X-650 F1000\n"
    "G1 Y-350\nG1 X-350\nG1 Y-150\nG0 Z-200\n";

pipeline::AlignOptions best_fit() { return test::best_fit_alignment(); }

// The rectangle's bottom (lines 7–10), its first side (line 7), line 8.
pipeline::AlignOptions datums() { return test::datum_alignment("7-10", "7", "8"); }

pipeline::ModelAlignment setup_of(const machine::Machine& m,
                                  const pipeline::AlignOptions& ao = best_fit()) {
  std::istringstream program(kProgram);
  return pipeline::program_setup(program, "<test>", m, model::ModelKind::ae_arm, {}, ao);
}

TEST(AlignmentExtension, ExtendedModelPredictsTheAlignedDeviation) {
  const machine::Machine m =
      machine::Machine::load(std::string(ABBE_TEST_DATA_DIR) + "/machines/sample.yaml");
  const pipeline::ModelAlignment a = setup_of(m);
  EXPECT_GT(a.absolute.points, 100u);
  EXPECT_LT(a.aligned.max_um, a.absolute.max_um);
  const model::ErrorModel base(m, model::ModelKind::ae_arm);
  const model::ErrorModel aligned =
      base.with_extension(std::make_shared<const pipeline::AlignmentExtension>(a.motion));
  model::ModelData d1, d2;
  double largest = 0;
  for (int i = 0; i <= 60; ++i) {  // on two edges of the rectangle (part points)
    model::EvalPoint p;
    p.p = i <= 30 ? Eigen::Vector3d(-650.0 + 10.0 * i, -150.0, -280.0)
                  : Eigen::Vector3d(-650.0, -150.0 - 200.0 * (i - 30) / 30.0, -280.0);
    p.tool_length = 200.0;
    p.dir = {-1, -1, -1};  // as the program reaches both edges (−X, then −Y)
    const Eigen::Vector3d e = base.evaluate(p, d1).e_um;
    const Eigen::Vector3d r = aligned.evaluate(p, d2).e_um;
    EXPECT_LT((r - pipeline::aligned_deviation_um(a.motion, p.p, e)).norm(), 1e-9);
    largest = std::max(largest, r.norm());
  }
  // Of the size of the aligned part (between its fragment points: + 0.5 µm).
  EXPECT_LE(largest, a.aligned.max_um + 0.5);
  EXPECT_GT(largest, 0.5 * a.aligned.max_um);
}

TEST(AlignmentExtension, RigidOnlyMachineLeavesNothingToCorrect) {
  const machine::Machine m =
      machine::Machine::load(std::string(ABBE_TEST_DATA_DIR) + "/align/rigid-only.yaml");
  for (const pipeline::AlignOptions& ao : {best_fit(), datums()}) {
    const pipeline::ModelAlignment a = setup_of(m, ao);
    EXPECT_GT(a.absolute.max_um, 1.0);
    // ae-arm is first order: θ × arm is a linearised rotation, which the exact
    // alignment removes up to θ²·arm ≈ (17 µrad)²·500 mm ≈ 1e-4 µm (measured 2.6e-5).
    EXPECT_LT(a.aligned.max_um, 1e-3);
  }
}

// compensate --align datums corrects what predict --align datums leaves: the
// same set-up (rigid motion and figures), not the best fit's.
TEST(AlignmentExtension, DatumSetUpIsThatOfPredictAlign) {
  const machine::Machine m =
      machine::Machine::load(std::string(ABBE_TEST_DATA_DIR) + "/machines/sample.yaml");
  const pipeline::ModelAlignment a = setup_of(m, datums());
  pipeline::PredictOptions po;
  std::istringstream program(kProgram);
  const pipeline::AlignedPrediction p =
      pipeline::predict_aligned(program, "<test>", m, po, datums(), {}, {});
  ASSERT_EQ(p.alignment.models.size(), 1u);
  const pipeline::ModelAlignment& b = p.alignment.models.front();
  EXPECT_EQ(a.motion.rotation, b.motion.rotation);
  EXPECT_EQ(a.motion.translation_mm, b.motion.translation_mm);
  EXPECT_EQ(a.aligned.max_um, b.aligned.max_um);
  const pipeline::ModelAlignment fit = setup_of(m);
  EXPECT_GT((a.rotation_urad - fit.rotation_urad).norm(), 0.1);
}

}  // namespace
}  // namespace abbe
