// `abbe import laser`: the laser-calibration export — every unit and its
// conversion (arc-seconds exactly, never taken as µrad), columns in any
// order, refusals with file, line, column and field, and the round trip into
// the ISO 230-2 evaluation and the component table.
#include "abbe/io/laser_export.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "abbe/diagnose/iso230.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/io/units.hpp"
#include "abbe/machine/component_table.hpp"

namespace abbe::io {
namespace {

const std::string kData = std::string(ABBE_TEST_DATA_DIR) + "/laser/";

LaserExport read(const std::string& text) {
  std::istringstream in(text);
  return read_laser_export(in, "laser.csv");
}

std::string exported(const std::string& component, const std::string& unit,
                     const std::string& rows =
                         "target,run,direction,reading\n0,1,up,1.5\n"
                         "0,2,up,2.5\n100,1,up,3\n100,2,up,4\n") {
  return fmt::format("# axis: {}\n# component: {}\n# units: {}\n{}", component.substr(2, 1),
                     component, unit, rows);
}

TEST(LaserExport, EveryUnitConverts) {
  struct Case {
    std::string component, unit;
    double factor;
  };
  const double arcsec_urad = units::kPi / 648000.0 * 1e6;
  for (const Case& c : {Case{"EXX", "µm", 1.0}, Case{"EYX", "um", 1.0}, Case{"EZY", "mm", 1000.0},
                        Case{"EAX", "arcsec", arcsec_urad}, Case{"EBY", "\"", arcsec_urad},
                        Case{"ECZ", "µrad", 1.0}, Case{"EAZ", "urad", 1.0},
                        Case{"EBX", "mm/m", 1000.0}, Case{"EBX", "ARCSEC", arcsec_urad}}) {
    const LaserExport d = read(exported(c.component, c.unit));
    ASSERT_EQ(d.readings.size(), 4u) << c.unit;
    EXPECT_EQ(d.component, c.component);
    EXPECT_DOUBLE_EQ(d.readings[0].value, 1.5 * c.factor) << c.unit;
    EXPECT_DOUBLE_EQ(d.readings[3].value, 4.0 * c.factor) << c.unit;
  }
  // 1″ = π/648000 rad = 4.84813681109536 µrad: never 1 µrad.
  EXPECT_NEAR(laser_unit_factor(LaserUnit::arcsec), 4.84813681109536, 1e-13);
  const LaserExport d = read(exported("EBX", "arcsec", "target,run,direction,reading\n0,1,up,1\n"));
  EXPECT_NEAR(d.readings[0].value, 4.84813681109536, 1e-13);
}

TEST(LaserExport, ColumnsInAnyOrderAndCase) {
  const LaserExport a = read(exported("EXX", "um"));
  const LaserExport b = read(
      exported("EXX", "um",
               "READING,Target,direction,RUN\n1.5,0,up,1\n2.5,0,up,2\n3,100,up,1\n4,100,up,2\n"));
  const LaserExport c =
      read(exported("EXX", "um",
                    "run;reading;direction;target;temperature\n1;1,5;up;0;20,1\n2;2,5;up;0;20,2\n"
                    "1;3;up;100;20,1\n2;4;up;100;20,3\n"));
  ASSERT_EQ(a.readings.size(), b.readings.size());
  ASSERT_EQ(a.readings.size(), c.readings.size());
  for (std::size_t i = 0; i < a.readings.size(); ++i) {
    for (const LaserExport* o : {&b, &c}) {
      EXPECT_EQ(o->readings[i].target_mm, a.readings[i].target_mm);
      EXPECT_EQ(o->readings[i].run, a.readings[i].run);
      EXPECT_EQ(o->readings[i].dir, a.readings[i].dir);
      EXPECT_EQ(o->readings[i].value, a.readings[i].value);
    }
  }
}

TEST(LaserExport, FilesWithMetadata) {
  const LaserExport x = load_laser_export(kData + "x-positioning-um.csv");
  EXPECT_EQ(x.axis, 'X');
  EXPECT_EQ(x.component, "EXX");
  EXPECT_FALSE(x.angular);
  ASSERT_TRUE(x.reference_mm);
  EXPECT_EQ(*x.reference_mm, 0.0);
  EXPECT_EQ(x.environment_compensation, "automatic");
  EXPECT_EQ(x.readings.size(), 18u);
  const LaserExport p = load_laser_export(kData + "x-pitch-arcsec.csv");
  EXPECT_EQ(p.component, "EBX");
  EXPECT_TRUE(p.angular);
  EXPECT_EQ(p.environment_compensation, "off");
  EXPECT_EQ(p.readings[1].target_mm, 100.0);
  EXPECT_NEAR(p.readings[1].value, 0.5 * 4.84813681109536, 1e-12);  // "0,50" arcsec
}

struct Refusal {
  std::string text;
  std::size_t line, column;
  std::string field, says;
};

class LaserExportRefuses : public ::testing::TestWithParam<Refusal> {};

// Read as a file of sections (one section: as read_laser_export reads it).
TEST_P(LaserExportRefuses, NamesFileLineColumnAndField) {
  const Refusal& r = GetParam();
  try {
    std::istringstream in(r.text);
    read_laser_exports(in, "laser.csv");
    FAIL() << "accepted:\n" << r.text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "laser.csv");
    EXPECT_EQ(e.where().line, r.line) << e.what();
    EXPECT_EQ(e.where().column, r.column) << e.what();
    EXPECT_EQ(e.where().field, r.field) << e.what();
    EXPECT_NE(e.message().find(r.says), std::string::npos) << e.what();
  }
}

const std::string kRows = "target,run,direction,reading\n0,1,up,1\n";

INSTANTIATE_TEST_SUITE_P(
    Cases, LaserExportRefuses,
    ::testing::Values(
        // A linear component in an angular unit and the reverse: refused, never reinterpreted.
        Refusal{exported("EXX", "arcsec"), 3, 10, "units",
                "EXX is linear but the unit arcsec is angular"},
        Refusal{exported("EBX", "um"), 3, 10, "units", "EBX is angular but the unit um is linear"},
        Refusal{exported("EBX", "mm"), 3, 10, "units", "angular but the unit mm is linear"},
        Refusal{exported("EXX", "mm/m"), 3, 10, "units", "linear but the unit mm/m is angular"},
        Refusal{exported("EXX", "inch"), 3, 10, "units", "unknown unit \"inch\""},
        Refusal{"# component: EXX\n# units: um\n" + kRows, 0, 0, "axis", "# axis:"},
        Refusal{"# axis: X\n# units: um\n" + kRows, 0, 0, "component", "# component:"},
        Refusal{"# axis: X\n# component: EXX\n" + kRows, 0, 0, "units", "# units:"},
        Refusal{"# axis: Y\n# component: EXX\n# units: um\n" + kRows, 2, 14, "component",
                "belongs to axis X, not Y"},
        Refusal{"# axis: X\n# component: EC0Y\n# units: urad\n" + kRows, 2, 14, "component",
                "not an ISO 230-1 component"},
        Refusal{"# axis: W\n# component: EXX\n# units: um\n" + kRows, 1, 9, "axis", "unknown axis"},
        Refusal{"# axis: X\n# axis: Y\n# component: EXX\n# units: um\n" + kRows, 2, 9, "axis",
                "given twice"},
        Refusal{exported("EXX", "um", "target,run,reading\n0,1,1\n"), 4, 1, "header",
                "no column `direction`"},
        Refusal{exported("EXX", "um", "target,run,direction,reading\n0,1,sideways,1\n"), 5, 5,
                "direction", "not a direction"},
        Refusal{exported("EXX", "um", "target,run,direction,reading\n0,0,up,1\n"), 5, 3, "run",
                "not a run number"},
        Refusal{exported("EXX", "um", "target,run,direction,reading\n0,1.5,up,1\n"), 5, 3, "run",
                "not a run number"},
        Refusal{exported("EXX", "um", "target,run,direction,reading\n0,1,up,abc\n"), 5, 8,
                "reading", "abc"},
        Refusal{exported("EXX", "um", "target,run,direction,reading\n0,1,up,1\n0,1,up,2\n"), 6, 3,
                "run", "already on line 5"},
        Refusal{"# axis: X\n# component: EXX\n# units: um\n# reference: 50\n" + kRows, 4, 14,
                "reference", "none of the targets"},
        Refusal{
            "# axis: X\n# component: EXX\n# units: um\n# environment compensation: maybe\n" + kRows,
            4, 29, "environment compensation", "not one of automatic, manual, off"}));

// Every rule is checked in every section, at the line of the whole file: a
// second section after a good first one (lines 1-6).
const std::string kFirst =
    "# axis: X\n# component: EXX\n# units: um\n"
    "target,run,direction,reading\n0,1,up,1\n0,2,up,2\n";

INSTANTIATE_TEST_SUITE_P(
    Sections, LaserExportRefuses,
    ::testing::Values(
        // The second section's unit does not fit its component (the first's would).
        Refusal{kFirst + "# axis: X\n# component: EBX\n# units: um\n" + kRows, 9, 10, "units",
                "EBX is angular but the unit um is linear"},
        Refusal{kFirst + "# axis: Y\n# component: EYY\n# units: arcsec\n" + kRows, 9, 10, "units",
                "EYY is linear but the unit arcsec is angular"},
        // Metadata the first section gave is not inherited.
        Refusal{kFirst + "# component: EYY\n# units: um\n" + kRows, 0, 0, "axis", "# axis:"},
        Refusal{kFirst + "# axis: Y\n# component: EYY\n# units: um\n" + kRows + "0,1,up,2\n", 12, 3,
                "run", "already on line 11"},
        Refusal{kFirst + "# axis: X\n# component: EXX\n# units: mm\n" + kRows, 8, 0, "component",
                "EXX is already the component of an earlier section"}));

// The runs file is what `abbe iso230` reads: its per-target means and s are
// those of the table written beside it (mean, s/√n).
TEST(LaserExport, RoundTripIntoIso230AndTheTable) {
  const LaserExport x = load_laser_export(kData + "x-positioning-um.csv");
  std::istringstream runs(laser_runs_csv(x));
  const auto results =
      diagnose::evaluate_iso230(diagnose::read_iso230_runs(runs, "runs.csv"), "runs.csv");
  ASSERT_EQ(results.size(), 1u);
  const diagnose::Iso230Result& r = results[0];
  EXPECT_EQ(r.component, "EXX");
  EXPECT_EQ(r.runs, 3);
  ASSERT_EQ(r.targets.size(), 3u);
  EXPECT_NEAR(r.targets[1].mean_up, (2.1 + 2.3 + 2.0) / 3.0, 1e-12);
  EXPECT_NEAR(r.targets[2].mean_down, (2.6 + 2.7 + 2.9) / 3.0, 1e-12);

  const machine::ComponentTable t = machine::ComponentTable::parse(laser_table_csv(x), "t.csv");
  ASSERT_TRUE(t.has_uncertainty());
  const machine::ComponentId exx{machine::Axis::x, 0};
  const auto* fwd = t.find(exx, machine::TableDirection::fwd);
  const auto* rev = t.find(exx, machine::TableDirection::rev);
  ASSERT_TRUE(fwd && rev);
  ASSERT_EQ(fwd->position_mm, (std::vector<double>{0.0, 100.0, 200.0}));
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(fwd->value[i], r.targets[i].mean_up, 1e-12);
    EXPECT_NEAR(rev->value[i], r.targets[i].mean_down, 1e-12);
    EXPECT_NEAR(fwd->u[i], r.targets[i].s_up / std::sqrt(3.0), 1e-12);
    EXPECT_NEAR(rev->u[i], r.targets[i].s_down / std::sqrt(3.0), 1e-12);
  }

  // One direction in arc-seconds: µrad in the runs file, a mean series.
  const LaserExport p = load_laser_export(kData + "x-pitch-arcsec.csv");
  std::istringstream prun(laser_runs_csv(p));
  const auto pr = diagnose::evaluate_iso230(diagnose::read_iso230_runs(prun, "p.csv"), "p.csv");
  ASSERT_EQ(pr.size(), 1u);
  EXPECT_EQ(pr[0].unit, "urad");
  EXPECT_NEAR(pr[0].targets[2].mean_up, 1.25 * 4.84813681109536, 1e-9);
  const machine::ComponentTable pt = machine::ComponentTable::parse(laser_table_csv(p), "p.csv");
  const auto* mean = pt.find({machine::Axis::x, 4}, machine::TableDirection::mean);
  ASSERT_TRUE(mean);
  EXPECT_NEAR(mean->value[1], 0.5166666666666667 * 4.84813681109536, 1e-9);
}

TEST(LaserExport, TableNeedsTwoRunsPerTarget) {
  const LaserExport d = read(exported("EXX", "um",
                                      "target,run,direction,reading\n0,1,up,1\n"
                                      "0,2,up,2\n100,1,up,3\n"));
  try {
    laser_table_csv(d);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 7u);  // 100,1,up,3: one run at target 100
    EXPECT_EQ(e.where().field, "run");
    EXPECT_NE(e.message().find("at least 2"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(laser_runs_csv(d));
}

}  // namespace
}  // namespace abbe::io
