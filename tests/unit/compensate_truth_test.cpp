// Compensation on the virtual machine: the tables of a noise-free virtual
// laser campaign drive the ae-arm model, the program is compensated with
// it, and the exact truth is evaluated along the compensated program. The
// deviation left (truth at the commanded points, measured against the
// model's prediction there, which verify puts within tol of the nominal
// path) must be at least 90 % smaller in RMS than the truth deviation along
// the original program.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "abbe/compensate/path_verifier.hpp"
#include "abbe/compensate/program_compensator.hpp"
#include "abbe/gcode/program.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/path/fragmenter.hpp"
#include "abbe/sim/laser_campaign.hpp"
#include "written_machine.hpp"

namespace abbe {
namespace {

TEST(CompensateTruth, NinetyPercentLessRmsDeviation) {
  sim::GeneratorOptions o;
  o.seed = 7;
  o.profile = "mazak";
  o.chain = "w X' b Y Z t";
  o.spacing_mm = 5.0;
  o.runs = 2;
  o.noise_scale = 0.0;
  o.angular_scale = 1.0;
  const sim::GeneratedMachine g = sim::generate_machine(o);
  const sim::CampaignResult result = sim::run_campaign(g);
  const machine::Machine m = test::written_machine(g, result, "compensate_truth");
  const model::ErrorModel em(m, model::ModelKind::ae_arm);

  gcode::InterpreterConfig config;
  config.tool_lengths = g.truth.tool_table;
  config.default_tool_length = g.truth.tool_length;
  config.initial_position = Eigen::Vector3d(0.0, 0.0, -g.truth.tool_length);

  // RMS over the feed points of a program of |truth − reference| (µm).
  auto rms = [&](const std::string& text, bool against_model) {
    std::istringstream in(text);
    path::Fragmenter fr(path::FragmentOptions{});
    model::ModelData data;
    double sum = 0.0;
    std::size_t n = 0;
    gcode::run_program(in, "p", config, [&](const gcode::Motion& mo) {
      fr.add(mo, [&](const path::PathPoint& p) {
        if (p.kind == gcode::MotionKind::rapid) return;
        sim::TipState tip;
        tip.p = p.p;
        tip.tool_length = p.tool_length;
        for (std::size_t k = 0; k < 3; ++k) tip.dir[k] = p.dir[k];
        Eigen::Vector3d d = g.truth.geometric_deviation_um(tip);
        if (against_model) {
          model::EvalPoint q;
          q.p = p.p;
          q.tool_length = p.tool_length;
          q.dir = p.dir;
          d -= em.evaluate(q, data).e_um;
        }
        sum += d.squaredNorm();
        ++n;
      });
    });
    return std::sqrt(sum / static_cast<double>(n));
  };

  for (const char* file : {"thesis-toolpath-1.ngc", "thesis-toolpath-2.ngc", "spline-slot.ngc",
                           "spline-slot-corner.ngc"}) {
    std::ifstream f(std::string(ABBE_SOURCE_DIR) + "/nc-samples/" + file, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    const std::string original = s.str();
    std::istringstream in(original);
    std::string compensated;
    compensate::compensate_program(in, file, config, em, compensate::CompensateOptions{},
                                   [&](const char* d, std::size_t k) { compensated.append(d, k); });
    const double before = rms(original, false);
    // Cut deviation = (truth − model)(c) + (c + model(c) − nominal): the
    // first RMS here, the second from verify; their sum bounds the RMS.
    const double model_gap = rms(compensated, true);
    std::istringstream vc(compensated), vo(original);
    const compensate::VerifyStats v =
        compensate::verify_program(vc, "out", vo, file, config, em, compensate::VerifyOptions{});
    const double after = model_gap + std::max(v.rms_um, v.backward_rms_um);
    std::printf(
        "%s: truth RMS deviation %.3f µm original; compensated ≤ %.4f µm (truth−model %.4f + "
        "verify %.4f), %.1f %% less\n",
        file, before, after, model_gap, std::max(v.rms_um, v.backward_rms_um),
        100.0 * (1.0 - after / before));
    EXPECT_LE(std::max(v.max_um, v.backward_max_um), 1.0) << file;
    EXPECT_GT(before, 1.0) << file;
    EXPECT_LT(after, 0.1 * before) << file;
  }
}

}  // namespace
}  // namespace abbe
