// The walk-through's demo (docs/getting-started.md §6): the sample machine's
// measured grid hides a thermal growth of Z over the two hours of its
// measurement — two lags in series, not an exponential of any τ, so not a
// candidate column of the diagnosis. The shipped file must be what its
// documented command makes, and the diagnosis of it must name the cause
// (kind, axis, direction and sign), and the extended model must gain on a
// fresh measurement of the same machine (new noise) what an oracle that
// knows the hidden drift gains, within 30 %.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "abbe/diagnose/diagnosis.hpp"
#include "abbe/io/measured_data.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/sim/effect.hpp"
#include "abbe/sim/truth_file.hpp"
#include "abbe/sim/validation_measurement.hpp"

namespace abbe::diagnose {
namespace {

const std::string kDir = std::string(ABBE_SOURCE_DIR) + "/machines/sample/";
// The hidden cause and the walk of the documented command (getting-started §6):
//   abbe simulate measure --truth machines/sample/truth.yaml --grid 100
//     --repeat 2 --one-setup --interval 9
//     --inject thermal_drift:Z:-12um:tau=2400,lag=900 --seed 1
//     -o machines/sample/measured-grid.csv
const char* const kHidden = "thermal_drift:Z:-12um:tau=2400,lag=900";

// The documented walk (two passes from one setup, 9 s per point), or the
// same two hours in one pass (18 s per point).
std::vector<sim::MeasuredPoint> measure_sample(bool with_drift, std::uint64_t seed,
                                               bool one_pass = false,
                                               const char* hidden = kHidden) {
  sim::GeneratedMachine g = sim::load_truth_file(kDir + "truth.yaml");
  if (with_drift) g.truth.effects.push_back(sim::parse_effect(hidden));
  sim::GridOptions go;
  go.spacing_mm = 100.0;
  go.tool_length = g.truth.tool_length;
  go.interval_s = one_pass ? 18.0 : 9.0;
  go.repeat = one_pass ? 1 : 2;
  go.one_setup = true;
  sim::default_box(g.truth, go.tool_length, go.lo, go.hi);
  return sim::measure(g.truth, sim::grid_points(go), 0.5, seed);
}

TEST(DiagnoseDemo, ShippedGridIsWhatItsCommandMakes) {
  std::ifstream in(kDir + "measured-grid.csv");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), sim::measured_to_csv(measure_sample(true, 1)));
}

TEST(DiagnoseDemo, NamesTheThermalGrowthOfZOnTheShippedGrid) {
  const machine::Machine m = machine::Machine::load(kDir + "machine.yaml");
  const io::MeasuredData data = io::load_measured_data(kDir + "measured-grid.csv");
  const Diagnosis d = diagnose(m, data, DiagnoseOptions{});
  ASSERT_FALSE(d.effects.empty());
  // The first effect is the cause: a drift in time of Z, getting more
  // negative (the spindle grows towards the table), named (significant, no
  // alternatives), with the most of the residual.
  const SelectedTerm& first = d.effects.front();
  EXPECT_EQ(first.term.kind, TermKind::thermal_drift) << first.term.label();
  EXPECT_EQ(first.term.direction, 2) << first.term.label();
  EXPECT_EQ(first.term.with_axis, -1) << first.term.label();
  ASSERT_FALSE(first.term.coef.empty());
  EXPECT_LT(first.term.coef[0], 0.0) << first.term.description();
  EXPECT_TRUE(first.significant);
  EXPECT_TRUE(first.ambiguous_with.empty());
  EXPECT_GT(first.explained_fraction, 0.5);
  // No other catalogue name: everything else is the drift's own shape
  // (more thermal drift of Z) or an `unexplained` remainder.
  for (const SelectedTerm& e : d.effects) {
    if (e.term.kind == TermKind::unexplained) continue;
    EXPECT_EQ(e.term.kind, TermKind::thermal_drift) << e.term.label();
    EXPECT_EQ(e.term.direction, 2) << e.term.label();
  }
  EXPECT_GT(d.gain_percent, 50.0);
}

TEST(DiagnoseDemo, GainsOnAFreshMeasurementWhatAnOracleGains) {
  const machine::Machine m = machine::Machine::load(kDir + "machine.yaml");
  const io::MeasuredData data = io::load_measured_data(kDir + "measured-grid.csv");
  const DiagnoseOptions plain;
  const Diagnosis d = diagnose(m, data, plain);
  const Overlay overlay = make_overlay(d, nullptr);
  // A fresh measurement (new noise), the same truth: the datum-only
  // held-out RMS without and with the overlay, and with the true drift
  // taken out (the oracle).
  const io::MeasuredData fresh = sim::to_measured_data(measure_sample(true, 2), "fresh");
  const io::MeasuredData oracle = sim::to_measured_data(measure_sample(false, 2), "oracle");
  const double before = diagnose(m, fresh, plain).baseline_holdout_rms_um;
  DiagnoseOptions extended;
  extended.extend = &overlay;
  const double after = diagnose(m, fresh, extended).baseline_holdout_rms_um;
  const double best = diagnose(m, oracle, plain).baseline_holdout_rms_um;
  const double gain = 1.0 - after / before, oracle_gain = 1.0 - best / before;
  EXPECT_GT(gain, 0.7 * oracle_gain) << after << " " << before << " " << best;
  EXPECT_GT(gain, 0.5);
}

TEST(DiagnoseDemo, OnePassTellsTimeFromZByTheCourseWithinEachLevel) {
  // What the design can and cannot see (getting-started §6): in one pass the
  // grid walks the Z levels in order, so time and Z go together level by
  // level; the drift is told from a scale of Z, or any function of z on the
  // levels, only by its course within each level (20 minutes of the two
  // hours). Here the data show it: the drift is named, and a scale of Z
  // measured the same way is named a scale, not a drift
  // (design_ambiguity.hpp; where the course is below the noise the drift is
  // ambiguous: DiagnoseDesignAmbiguity.DriftOnLevelsWalkedInOrderIsToldByItsCourseWithinALevel).
  const machine::Machine m = machine::Machine::load(kDir + "machine.yaml");
  for (const char* hidden : {kHidden, "scale:Z:-12ppm"}) {
    const bool drift = hidden == kHidden;
    const io::MeasuredData one =
        sim::to_measured_data(measure_sample(true, 1, true, hidden), "one pass");
    const Diagnosis d = diagnose(m, one, DiagnoseOptions{});
    ASSERT_FALSE(d.effects.empty());
    const SelectedTerm& first = d.effects.front();
    EXPECT_EQ(first.term.kind, drift ? TermKind::thermal_drift : TermKind::scale)
        << first.term.label();
    EXPECT_EQ(first.term.direction, 2) << first.term.label();
    EXPECT_TRUE(first.ambiguous_with.empty()) << first.term.label();
    for (const SelectedTerm& e : d.effects) {
      if (e.term.kind == TermKind::unexplained || !e.ambiguous_with.empty()) continue;
      EXPECT_EQ(e.term.kind, first.term.kind) << hidden << ": " << e.term.label();
    }
  }
}

}  // namespace
}  // namespace abbe::diagnose
