// The tables' uncertainty in the diagnosis (table_uncertainty.hpp): zero
// in, zero out; linear in the campaign's uncertainties; the refusal of a
// machine without any; and what it is for: on the sample machine, whose
// tables come from a campaign with reading noise, a drift in time of Y on a
// serpentine grid is pulled off its true value by the tables' errors (the
// time of a serpentine follows the position) by several times the data's u,
// and within the combined u.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "abbe/diagnose/diagnosis.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/sim/effect.hpp"
#include "abbe/sim/error_component.hpp"
#include "abbe/sim/truth_file.hpp"
#include "abbe/sim/validation_measurement.hpp"

namespace abbe::diagnose {
namespace {

const std::string kDir = std::string(ABBE_SOURCE_DIR) + "/machines/sample/";

// The sample machine measured on an 80 mm grid, twice (two sets, each its
// own datum), 5 s per point, noise 0.5 µm, with `hidden` injected.
io::MeasuredData measure_grid(const char* hidden, std::uint64_t seed) {
  sim::GeneratedMachine g = sim::load_truth_file(kDir + "truth.yaml");
  g.truth.effects.push_back(sim::parse_effect(hidden));
  sim::GridOptions go;
  go.spacing_mm = 80.0;
  go.tool_length = g.truth.tool_length;
  go.repeat = 2;
  sim::default_box(g.truth, go.tool_length, go.lo, go.hi);
  return sim::to_measured_data(sim::measure(g.truth, sim::grid_points(go), 0.5, seed), "<grid>");
}

// The sample machine with the uncertainty of its own campaign: every table
// value the mean of `runs` readings with the truth file's reading noise σ,
// so u = σ/√runs (the tables' values, per component), times `factor`.
machine::Machine sample_with_campaign_u(double factor) {
  const sim::GeneratedMachine g = sim::load_truth_file(kDir + "truth.yaml");
  machine::MachineSpec spec = machine::Machine::load(kDir + "machine.yaml").spec();
  spec.uncertainty = machine::CampaignUncertainty{};
  spec.uncertainty.given = true;
  for (std::size_t j = 0; j < 3; ++j)
    for (std::size_t c = 0; c < 6; ++c)
      spec.uncertainty.component[j * 6 + c] =
          factor * g.campaign.axes[j].sigma[c] / std::sqrt(static_cast<double>(g.campaign.runs));
  return machine::Machine(spec);
}

DiagnoseOptions with_draws(std::size_t draws) {
  DiagnoseOptions o;
  o.tables.draws = draws;
  o.tables.seed = 3;
  return o;
}

const SelectedTerm* drift_of(const Diagnosis& d, int direction) {
  for (const SelectedTerm& st : d.effects)
    if (st.term.kind == TermKind::thermal_drift && st.term.direction == direction &&
        st.term.with_axis < 0)
      return &st;
  return nullptr;
}

TEST(DiagnoseTableUncertainty, ZeroUncertaintyAddsNothing) {
  const io::MeasuredData data = measure_grid("thermal_drift:Y:5um:tau=2500", 4);
  const machine::Machine m = sample_with_campaign_u(0.0);
  const Diagnosis plain = diagnose(m, data, DiagnoseOptions{});
  const Diagnosis d = diagnose(m, data, with_draws(10));
  EXPECT_EQ(d.tables.draws, 10u);
  ASSERT_EQ(d.effects.size(), plain.effects.size());
  for (std::size_t i = 0; i < d.effects.size(); ++i) {
    const SelectedTerm& st = d.effects[i];
    if (st.term.kind == TermKind::unexplained) continue;
    ASSERT_EQ(st.stderr_tables.size(), st.term.coef.size()) << st.term.label();
    for (double u : st.stderr_tables) EXPECT_NEAR(u, 0.0, 1e-9) << st.term.label();
    ASSERT_EQ(st.term.stderr_.size(), plain.effects[i].term.stderr_.size());
    for (std::size_t c = 0; c < st.term.stderr_.size(); ++c)
      EXPECT_NEAR(st.term.stderr_[c], plain.effects[i].term.stderr_[c], 1e-12);
    EXPECT_NEAR(st.term.searched_stderr, plain.effects[i].term.searched_stderr, 1e-9);
  }
  for (const SelectedTerm& st : d.datum)
    for (double u : st.stderr_tables) EXPECT_NEAR(u, 0.0, 1e-9) << st.term.label();
}

TEST(DiagnoseTableUncertainty, TheTablesPartIsLinearInTheCampaignsUncertainty) {
  // The same seeded deviates scaled by 2: the shifts of a linear fit double
  // (the models are linear in the table values to within their second-order
  // terms, far below 1 %).
  const io::MeasuredData data = measure_grid("thermal_drift:Y:5um:tau=2500", 4);
  const Diagnosis one = diagnose(sample_with_campaign_u(1.0), data, with_draws(12));
  const Diagnosis two = diagnose(sample_with_campaign_u(2.0), data, with_draws(12));
  const SelectedTerm* a = drift_of(one, 1);
  const SelectedTerm* b = drift_of(two, 1);
  ASSERT_TRUE(a && b);
  ASSERT_FALSE(a->stderr_tables.empty());
  ASSERT_FALSE(b->stderr_tables.empty());
  EXPECT_GT(a->stderr_tables[0], 0.0);
  EXPECT_NEAR(b->stderr_tables[0], 2.0 * a->stderr_tables[0], 0.01 * a->stderr_tables[0]);
  EXPECT_NEAR(b->searched_stderr_tables, 2.0 * a->searched_stderr_tables,
              0.01 * a->searched_stderr_tables);
  // The data's part is the fit's own, whatever the tables' uncertainty.
  EXPECT_NEAR(a->stderr_data[0], b->stderr_data[0], 1e-12);
}

TEST(DiagnoseTableUncertainty, TheDriftsTrueValueLiesWithinTheCombinedUncertainty) {
  // Truth: Y drifts by 5 µm with τ 2500 s. The sample machine's tables
  // carry its campaign's reading noise; on the serpentine their errors
  // correlate with time and pull the drift to ≈ 5.7 µm, τ ≈ 3000 s. The
  // data's u (≈ 0.1 µm) puts the truth ≈ 7 u away; with the tables' part
  // (≈ 0.4 µm) it lies within 2.5 u. 40 draws: u to ≈ 11 %.
  const io::MeasuredData data = measure_grid("thermal_drift:Y:5um:tau=2500", 4);
  const Diagnosis d = diagnose(sample_with_campaign_u(1.0), data, with_draws(40));
  const SelectedTerm* drift = drift_of(d, 1);
  ASSERT_NE(drift, nullptr);
  ASSERT_FALSE(drift->stderr_data.empty());
  const double value = drift->term.coef[0];
  EXPECT_GT(std::abs(value - 5.0), 3.0 * drift->stderr_data[0])
      << "the data's u alone already covers the truth: the case no longer shows the tables' part";
  EXPECT_LE(std::abs(value - 5.0), 2.5 * drift->term.stderr_[0]) << drift->term.description();
  EXPECT_LE(std::abs(drift->term.tau_s - 2500.0), 2.5 * drift->term.searched_stderr)
      << drift->term.description();
  EXPECT_TRUE(drift->significant);
  // The report says which part is which.
  const std::string text = report_text(d);
  EXPECT_NE(text.find("every u holds the data's and the tables' uncertainty"), std::string::npos)
      << text;
  EXPECT_NE(text.find("u from the data and from the tables: value"), std::string::npos) << text;
  const std::string json = report_json(d);
  EXPECT_NE(json.find("\"stderr_tables\""), std::string::npos);
  EXPECT_NE(json.find("\"table_uncertainty\""), std::string::npos);
}

TEST(DiagnoseTableUncertainty, PropagatedByDefaultWhereTheMachineGivesOne) {
  const io::MeasuredData data = measure_grid("thermal_drift:Y:5um:tau=2500", 4);
  const Diagnosis by_default = diagnose(sample_with_campaign_u(1.0), data, DiagnoseOptions{});
  EXPECT_TRUE(by_default.tables.available);
  EXPECT_EQ(by_default.tables.draws, kDefaultTableDraws);
  const SelectedTerm* drift = drift_of(by_default, 1);
  ASSERT_NE(drift, nullptr);
  EXPECT_FALSE(drift->stderr_tables.empty());
  const Diagnosis off = diagnose(sample_with_campaign_u(1.0), data, with_draws(0));
  EXPECT_TRUE(off.tables.available);
  EXPECT_EQ(off.tables.draws, 0u);
  ASSERT_NE(drift_of(off, 1), nullptr);
  EXPECT_TRUE(drift_of(off, 1)->stderr_tables.empty());
  EXPECT_NE(report_text(off).find("every u is the data's alone"), std::string::npos);
  // A machine without one: nothing propagated, nothing said.
  const Diagnosis plain =
      diagnose(machine::Machine::load(kDir + "machine.yaml"), data, DiagnoseOptions{});
  EXPECT_FALSE(plain.tables.available);
  EXPECT_EQ(plain.tables.draws, 0u);
  EXPECT_EQ(report_text(plain).find("every u"), std::string::npos);
}

TEST(DiagnoseTableUncertainty, RefusedWithoutAnUncertaintyToPropagate) {
  const io::MeasuredData data = measure_grid("scale:X:10ppm", 1);
  const machine::Machine plain = machine::Machine::load(kDir + "machine.yaml");
  try {
    diagnose(plain, data, with_draws(10));
    FAIL() << "no uncertainty, no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "uncertainty");
    EXPECT_NE(e.where().file.find("machine.yaml"), std::string::npos) << e.where().file;
  }
  EXPECT_THROW(diagnose(sample_with_campaign_u(1.0), data, with_draws(1)), std::invalid_argument);
}

}  // namespace
}  // namespace abbe::diagnose
