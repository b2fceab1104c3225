// `abbe import laser` with several components in one export file: one
// section per component (a metadata line after readings starts the next),
// each read and checked as a file of its own — its units converted or
// refused for its component — with the line numbers of the whole file; the
// runs file and the table hold every section. Data: tests/data/laser
// (hand-written, see its README.md). The refusals of every section:
// laser_export_test.cpp (LaserExportRefuses, Sections).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "abbe/diagnose/iso230.hpp"
#include "abbe/io/laser_export.hpp"
#include "abbe/machine/component_table.hpp"

namespace abbe::io {
namespace {

const std::string kData = std::string(ABBE_TEST_DATA_DIR) + "/laser/";

TEST(LaserSections, ThreeComponentsInOneFile) {
  const std::vector<LaserExport> s = load_laser_exports(kData + "three-components.csv");
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0].component, "EXX");
  EXPECT_EQ(s[1].component, "EBX");
  EXPECT_EQ(s[2].component, "EYY");
  EXPECT_EQ(s[2].axis, 'Y');
  EXPECT_EQ(s[0].readings.size(), 8u);
  EXPECT_EQ(s[1].readings.size(), 4u);
  EXPECT_EQ(s[2].readings.size(), 4u);
  // Each section's unit: µm as is, mm/m → µrad (×1000), mm → µm (×1000).
  EXPECT_DOUBLE_EQ(s[0].readings[2].value, 3.9);
  EXPECT_NEAR(s[1].readings[1].value, 4.0, 1e-12);
  EXPECT_NEAR(s[2].readings[1].value, 2.1, 1e-12);
  // Each section's metadata, and the file's line numbers.
  ASSERT_TRUE(s[2].reference_mm);
  EXPECT_EQ(*s[2].reference_mm, -100.0);
  EXPECT_EQ(s[2].environment_compensation, "manual");
  EXPECT_EQ(s[1].environment_compensation, "");
  EXPECT_EQ(s[0].readings.front().line, 10u);
  EXPECT_EQ(s[1].readings.front().line, 23u);
  EXPECT_EQ(s[2].readings.back().line, 36u);

  // The runs file: every section, into the ISO 230-2 evaluation.
  std::istringstream runs(laser_runs_csv(s));
  const auto results =
      diagnose::evaluate_iso230(diagnose::read_iso230_runs(runs, "runs.csv"), "runs.csv");
  ASSERT_EQ(results.size(), 3u);
  // The table: every component, with its uncertainty column.
  const machine::ComponentTable t = machine::ComponentTable::parse(laser_table_csv(s), "t.csv");
  EXPECT_TRUE(t.has_uncertainty());
  EXPECT_TRUE(t.find({machine::Axis::x, 0}, machine::TableDirection::fwd));
  EXPECT_TRUE(t.find({machine::Axis::x, 0}, machine::TableDirection::rev));
  const auto* ebx = t.find({machine::Axis::x, 4}, machine::TableDirection::mean);
  ASSERT_TRUE(ebx);
  EXPECT_NEAR(ebx->value[1], 5.0, 1e-12);  // (4 + 6) / 2 µrad at 200 mm
  const auto* eyy = t.find({machine::Axis::y, 1}, machine::TableDirection::mean);
  ASSERT_TRUE(eyy);
  EXPECT_NEAR(eyy->value[1], 2.0, 1e-12);  // (2.1 + 1.9) / 2 µm at 0 mm
}

// A file with one section reads as read_laser_export reads it.
TEST(LaserSections, OneSectionIsTheSingleComponentExport) {
  for (const char* name : {"x-positioning-um.csv", "x-pitch-arcsec.csv"}) {
    const std::vector<LaserExport> s = load_laser_exports(kData + name);
    const LaserExport one = load_laser_export(kData + name);
    ASSERT_EQ(s.size(), 1u);
    EXPECT_EQ(laser_runs_csv(s), laser_runs_csv(one)) << name;
    EXPECT_EQ(laser_table_csv(s), laser_table_csv(one)) << name;
  }
}

}  // namespace
}  // namespace abbe::io
