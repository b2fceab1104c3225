// Per-component reference conventions in the machine file: the keys and
// their refusals, what each convention leaves free (from the chain), and the
// property that a table differing only by a convention's free constant or
// slope (with the squareness that goes with it) gives the same aligned
// prediction through Machine::load and predict_aligned.
#include "abbe/machine/reference_conventions.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/pipeline/aligned_prediction.hpp"
#include "minimal_machine_text.hpp"

namespace abbe::machine {
namespace {

const std::string& kDir = abbe::testing::kMachinesDir;
const std::string& kMachine = abbe::testing::kMinimalMachine;
using abbe::testing::AppendedKey;
using abbe::testing::AppendedKeyRejects;

TEST(ReferenceConventions, OldFilesAreAbsolute) {
  const Machine m = Machine::parse(kMachine, "m.yaml", kDir);
  EXPECT_FALSE(m.spec().conventions.any());
  const ConventionAnalysis a = analyse_conventions(m);
  EXPECT_FALSE(a.any);
  EXPECT_TRUE(a.notes.empty());
}

// Chain w X' b Y Z t: the table of docs/models.md, line by line.
TEST(ReferenceConventions, WhatEachConventionLeavesFree) {
  const std::string conv = R"(conventions:
  squareness: independent
  EXX: {reference_mm: -990}
  EYX: {reference_mm: -990, slope_removed: true}
  EBX: {reference_mm: -990, relative: true}
  EAY: {reference_mm: 0, relative: true}
  EBY: {reference_mm: 0, relative: true}
  ECY: {reference_mm: 0, relative: true}
  EAZ: {reference_mm: 0, relative: true}
  EYZ: {reference_mm: 0, slope_removed: true}
)";
  const Machine m = Machine::parse(kMachine + conv, "m.yaml", kDir);
  const ConventionAnalysis a = analyse_conventions(m);
  EXPECT_TRUE(a.any);
  EXPECT_FALSE(a.aligned_determined);  // slopes and tilts without their squareness
  const std::string all = fmt::format("{}", fmt::join(a.notes, "\n"));
  for (const char* says :
       {"EXX: zeroed at -990 mm: a constant offset, absorbed by the set-up",
        "EYX: slope removed, a shear in the XY plane: NOT absorbed — EC0Y",
        "EBX: relative to -990 mm: a rotation of the part about the reflector, absorbed",
        "EAY: relative to 0 mm, a shear in the YZ plane: NOT absorbed — EA0Z",
        "EBY: relative to 0 mm, a shear in the XZ plane: NOT absorbed — EB0Z",
        "ECY: relative to 0 mm: a constant offset, absorbed",
        "EAZ: relative to 0 mm: a constant offset, absorbed",
        "EYZ: slope removed, a shear in the YZ plane: NOT absorbed — EA0Z"})
    EXPECT_NE(all.find(says), std::string::npos) << says << "\n" << all;

  const Machine same = Machine::parse(
      kMachine + std::string(conv).replace(conv.find("independent"), 11, "same_reference"),
      "m.yaml", kDir);
  const ConventionAnalysis b = analyse_conventions(same);
  EXPECT_TRUE(b.aligned_determined);
  EXPECT_NE(fmt::format("{}", fmt::join(b.notes, "\n"))
                .find("EYX: slope removed, a shear in the XY plane: absorbed by EC0Y"),
            std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(
    Conventions, AppendedKeyRejects,
    ::testing::Values(
        AppendedKey{"conventions:\n  EXX: {reference_mm: -990, slope_removed: true}\n", 23,
                    "conventions.EXX.slope_removed", "positioning component"},
        AppendedKey{"conventions:\n  EXX: {reference_mm: -990, relative: true}\n", 23,
                    "conventions.EXX.relative", "unknown key"},
        AppendedKey{"conventions:\n  EBX: {reference_mm: -990}\n", 23, "conventions.EBX.relative",
                    "relative: true"},
        AppendedKey{"conventions:\n  EYX: {slope_removed: true}\n", 23,
                    "conventions.EYX.reference_mm", "missing key"},
        AppendedKey{"conventions:\n  EYX: {reference_mm: 50}\n", 23, "conventions.EYX.reference_mm",
                    "outside the measured range"},
        AppendedKey{"conventions:\n  EYX: {reference_mm: .nan}\n", 23,
                    "conventions.EYX.reference_mm", "finite"},
        AppendedKey{"conventions:\n  EYX: {reference_mm: 0, slope_removed: maybe}\n", 23,
                    "conventions.EYX.slope_removed", "not true or false"},
        AppendedKey{"conventions:\n  squareness: measured\n", 23, "conventions.squareness",
                    "same_reference or independent"},
        AppendedKey{"conventions:\n  EC0Y: {reference_mm: 0}\n", 23, "conventions.EC0Y",
                    "not a component name"}));

// The property: tables that differ only by the free constant (zeroed EXX,
// EZY; relative ECY) and slope (EYX, with EC0Y + 1000·κ; relative EBY with
// EB0Z − θ), read from machine files that declare those conventions with
// `squareness: same_reference`, give the same prediction of the part after a
// best fit (ae-arm, 5·10⁻⁴ µm), while the absolute predictions differ.
TEST(ReferenceConventions, FreeConstantsAndSlopesGiveTheSameAlignedPrediction) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / fmt::format("abbe-conv-{}", ::getpid());
  fs::create_directories(dir);
  const double c_exx = 3.7, kappa = 0.004, c_ezy = -2.2, theta_ecy = 6.0, theta_eby = 9.0;
  auto write = [&](const std::string& name, bool shifted) {
    std::string csv = "axis,component,position_mm,direction,value\n";
    for (int i = 0; i <= 11; ++i) {
      const double x = -990.0 + 90.0 * i;
      csv +=
          fmt::format("X,EXX,{},mean,{}\n", x, 2.0 * std::sin(0.01 * x) + (shifted ? c_exx : 0.0));
      csv += fmt::format("X,EYX,{},mean,{}\n", x,
                         1.5 * std::cos(0.013 * x) + (shifted ? kappa * x : 0.0));
      csv += fmt::format("X,EBX,{},mean,{}\n", x, 4.0 * std::sin(0.004 * x));
    }
    for (int i = 0; i <= 10; ++i) {
      const double y = -500.0 + 50.0 * i;
      csv +=
          fmt::format("Y,EZY,{},mean,{}\n", y, 1.1 * std::sin(0.02 * y) + (shifted ? c_ezy : 0.0));
      csv += fmt::format("Y,ECY,{},mean,{}\n", y,
                         3.0 * std::cos(0.01 * y) + (shifted ? theta_ecy : 0.0));
      csv += fmt::format("Y,EBY,{},mean,{}\n", y,
                         2.0 * std::sin(0.011 * y) + (shifted ? theta_eby : 0.0));
      csv += fmt::format("Y,EAY,{},mean,{}\n", y, 1.0 * std::sin(0.017 * y));
    }
    std::ofstream(dir / (name + ".csv")) << csv;
    const double ec0y = 14.5 + (shifted ? 1000.0 * kappa : 0.0);
    const double eb0z = -24.3 - (shifted ? theta_eby : 0.0);
    std::string yaml = kMachine;
    yaml.replace(yaml.find("sample-errors.csv"), 17, name + ".csv");
    yaml += fmt::format(
        "squareness: {{EC0Y: {}, EB0Z: {}, EA0Z: 13.7}}\n"
        "conventions:\n  squareness: same_reference\n  EXX: {{reference_mm: -990}}\n"
        "  EYX: {{reference_mm: -990, slope_removed: true}}\n  EZY: {{reference_mm: 0}}\n"
        "  ECY: {{reference_mm: 0, relative: true}}\n  EBY: {{reference_mm: 0, relative: true}}\n",
        ec0y, eb0z);
    std::ofstream(dir / (name + ".yaml")) << yaml;
    return Machine::load((dir / (name + ".yaml")).string());
  };
  const Machine a = write("a", false);
  const Machine b = write("b", true);
  EXPECT_TRUE(analyse_conventions(a).aligned_determined);

  std::string points = "x,y,z\n";
  for (double x : {-900.0, -600.0, -300.0, -50.0})
    for (double y : {-450.0, -250.0, -30.0})
      for (double z : {-400.0, -150.0}) points += fmt::format("{},{},{}\n", x, y, z);
  auto aligned = [&](const Machine& m, std::vector<Eigen::Vector3d>& abs) {
    pipeline::PredictOptions po;
    po.input = pipeline::PredictInput::points;
    pipeline::AlignOptions ao;
    ao.method = pipeline::AlignMethod::best_fit;
    std::istringstream in(points);
    std::vector<Eigen::Vector3d> out;
    const auto pred = pipeline::predict_aligned(
        in, "p.csv", m, po, ao, {},
        [&](const model::EvalPoint&, std::size_t, const std::vector<model::Deviation>& devs,
            const std::vector<double>&, const std::vector<Eigen::Vector3d>& al) {
          abs.push_back(devs[0].e_um);
          out.push_back(al[0]);
        });
    EXPECT_TRUE(pred.summary.conventions.any);
    EXPECT_NE(pipeline::summary_table(pred.summary).find("(--align) is determined"),
              std::string::npos);
    return out;
  };
  std::vector<Eigen::Vector3d> abs_a, abs_b;
  const auto ra = aligned(a, abs_a);
  const auto rb = aligned(b, abs_b);
  ASSERT_EQ(ra.size(), 24u);
  double worst = 0.0, abs_diff = 0.0;
  for (std::size_t i = 0; i < ra.size(); ++i) {
    worst = std::max(worst, (ra[i] - rb[i]).norm());
    abs_diff = std::max(abs_diff, (abs_a[i] - abs_b[i]).norm());
  }
  EXPECT_LT(worst, 5e-4);
  EXPECT_GT(abs_diff, 1.0);  // the absolute prediction is not determined
  fs::remove_all(dir);
}

}  // namespace
}  // namespace abbe::machine
