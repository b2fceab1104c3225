#pragma once
// Shared by the diagnose_*_test.cpp files: a virtual machine whose laser
// campaign is noise-free (so the error model matches the truth to first
// order), measured at random tool-tip positions with random directions of
// motion and increasing time, plus helpers to turn the measurement into
// measured data and to fit an oracle.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "abbe/diagnose/diagnosis.hpp"
#include "abbe/diagnose/selection.hpp"
#include "abbe/io/measured_data.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/sim/laser_campaign.hpp"
#include "abbe/sim/truth_generator.hpp"
#include "abbe/sim/validation_measurement.hpp"

namespace abbe::diagnose::testing {

struct VirtualMachine {
  sim::GeneratedMachine generated;
  machine::Machine machine;
};

// The generator's "mazak" machine (seed 7) with its laser campaign's tables,
// or another seed, profile or chain (empty: the generator's default chain);
// campaign_noise_scale 0 makes the campaign noise-free.
inline VirtualMachine build_virtual_machine(bool strip_short_waves, const std::string& name,
                                            double campaign_noise_scale = 0.0,
                                            std::uint64_t seed = 7,
                                            const std::string& profile = "mazak",
                                            const std::string& chain = "") {
  {
    sim::GeneratorOptions go;
    go.seed = seed;
    go.profile = profile;
    if (!chain.empty()) go.chain = chain;
    go.noise_scale = campaign_noise_scale;
    sim::GeneratedMachine g = sim::generate_machine(go);
    // The generator gives every positioning component a 10 mm ballscrew cycle
    // that the 25 mm tables cannot see: a real hidden effect (found by
    // DiagnoseSample.FindsTheScrewCycle). Remove waves shorter than two table
    // intervals here, so that "noise only" means noise only.
    for (auto& axis : g.truth.axes)
      for (auto& c : axis.components) {
        if (!strip_short_waves) break;
        std::vector<sim::Wave> keep;
        for (const auto& w : c.waves)
          if (w.wavelength >= 2.0 * go.spacing_mm) keep.push_back(w);
        c.waves = keep;
      }
    const sim::CampaignResult r = sim::run_campaign(g);
    // One directory per process: ctest runs tests of this binary in parallel.
    const auto dir =
        std::filesystem::path(::testing::TempDir()) / (name + "_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    { std::ofstream(dir / "errors.csv") << sim::table_to_csv(r); }
    machine::Machine m =
        machine::Machine::parse(sim::machine_to_yaml(g, r, "errors.csv"), "<vm>", dir.string());
    std::filesystem::remove_all(dir);  // the tables are read: nothing left behind
    return VirtualMachine{std::move(g), std::move(m)};
  }
}

inline const VirtualMachine& virtual_machine() {
  static const VirtualMachine vm = build_virtual_machine(true, "abbe_diagnose_vm");
  return vm;
}
// The generator's machine as is (with its 10 mm ballscrew cycle).
inline const VirtualMachine& virtual_machine_with_screw_cycle() {
  static const VirtualMachine vm = build_virtual_machine(false, "abbe_diagnose_vm_screw");
  return vm;
}

// Random tool-tip positions in [lo, hi], random last directions, 5 s apart.
inline std::vector<sim::TipState> random_tips(const sim::TruthMachine& truth, int n,
                                              std::uint64_t seed, Eigen::Vector3d lo,
                                              Eigen::Vector3d hi, const std::string& set = "run") {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<sim::TipState> tips;
  for (int i = 0; i < n; ++i) {
    sim::TipState t;
    for (int k = 0; k < 3; ++k) t.p[k] = lo[k] + (hi[k] - lo[k]) * u(rng);
    t.tool_length = truth.tool_length;
    for (auto& d : t.dir) d = u(rng) < 0.5 ? -1 : 1;
    t.time = 5.0 * i;
    t.set = set;
    tips.push_back(t);
  }
  return tips;
}

inline void full_box(const sim::TruthMachine& truth, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  sim::default_box(truth, truth.tool_length, lo, hi);
}

inline io::MeasuredData to_measured(const std::vector<sim::MeasuredPoint>& pts) {
  return sim::to_measured_data(pts, "<vm>");
}

// Held-out gain of a fit of the given terms beyond the datum (an offset per
// set and measured direction, always fitted): 1 − sqrt(CV SSE with the
// terms / CV SSE of the datum alone), as the diagnosis measures its gain.
inline double oracle_gain(const Problem& pb, const std::vector<Term>& terms, int folds,
                          std::uint64_t seed) {
  std::vector<Term> datum;
  for (const std::string& set : pb.sets)
    for (int i = 0; i < 3; ++i) {
      if (!pb.direction_present[static_cast<std::size_t>(i)]) continue;
      Term t;
      t.kind = TermKind::setup_offset;
      t.axis = i;
      t.direction = i;
      t.set = set;
      datum.push_back(t);
    }
  auto cv = [&](const std::vector<Term>& ts) {
    Eigen::Index cols = 0;
    for (const Term& t : ts) cols += t.columns();
    Eigen::MatrixXd X(static_cast<Eigen::Index>(pb.obs.size()), cols);
    Eigen::Index c = 0;
    for (const Term& t : ts) {
      X.middleCols(c, t.columns()) = term_columns(pb, t);
      c += t.columns();
    }
    return cross_validated_sse(pb, X, pb.y, point_folds(pb.points.size(), folds, seed), folds);
  };
  std::vector<Term> all = datum;
  for (const Term& t : terms)
    if (t.kind != TermKind::setup_offset) all.push_back(t);  // a setup offset is the datum
  return 1.0 - std::sqrt(cv(all) / cv(datum));
}

}  // namespace abbe::diagnose::testing
