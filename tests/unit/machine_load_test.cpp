// The YAML machine file: a complete file, and every rejection with the file,
// line and field it names.
#include <gtest/gtest.h>

#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "minimal_machine_text.hpp"

namespace abbe::machine {
namespace {

const std::string& kDir = abbe::testing::kMachinesDir;

TEST(MachineLoad, SampleMachine) {
  Machine m = Machine::load(kDir + "/sample.yaml");
  EXPECT_EQ(m.name(), "sample machine (synthetic)");
  EXPECT_EQ(m.chain().text(), "w X' b Y Z t");
  EXPECT_EQ(m.travel(Axis::x).min, -990.0);
  EXPECT_EQ(m.travel(Axis::z).max, 0.0);
  EXPECT_EQ(m.tool_length(), 130.0);
  EXPECT_EQ(m.tool_table().at(2), 95.5);
  EXPECT_EQ(m.work_offsets()[1], Eigen::Vector3d(-500.0, -250.0, -400.0));
  EXPECT_EQ(m.work_offsets()[2], Eigen::Vector3d::Zero());
  EXPECT_EQ(m.squareness().eb0z, -24.362);
  EXPECT_EQ(m.out_of_range(), OutOfRangePolicy::clamp);
  const AxisRecord& y = m.record(Axis::y);
  EXPECT_TRUE(y.present);
  EXPECT_EQ(y.point[0], Eigen::Vector3d(-480.0, -250.0, -300.0));  // EXY override
  EXPECT_EQ(y.point[1], Eigen::Vector3d(-500.0, -250.0, -300.0));  // from `all`
  EXPECT_EQ(y.measured_axes(), Eigen::Vector3d(-500.0, -250.0, -150.0));
  EXPECT_TRUE(m.table().bidirectional({Axis::x, 0}));
  EXPECT_EQ(m.table().series().size(), 21u);  // 3 axes × (5 mean + fwd + rev)
}

const std::string& kGood = abbe::testing::kMinimalMachine;

std::string replace(std::string text, const std::string& from, const std::string& to) {
  auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return text.replace(pos, from.size(), to);
}

TEST(MachineLoad, GoodTextParses) {
  Machine m = Machine::parse(kGood, "m.yaml", kDir);
  EXPECT_EQ(m.record(Axis::z).point[2], Eigen::Vector3d(-500.0, -250.0, -250.0));
  EXPECT_EQ(m.out_of_range(), OutOfRangePolicy::clamp);
}

TEST(MachineLoad, ToolDiametersAreOptional) {
  EXPECT_TRUE(Machine::parse(kGood, "m.yaml", kDir).tool_diameters().empty());
  const Machine m = Machine::parse(replace(kGood, "tool_length: 130.0\n",
                                           "tool_length: 130.0\ntool_diameters: {2: 12.7, 7: 6}\n"),
                                   "m.yaml", kDir);
  EXPECT_EQ(m.tool_diameters().size(), 2u);
  EXPECT_EQ(m.tool_diameters().at(2), 12.7);
  EXPECT_EQ(m.tool_diameters().at(7), 6.0);
}

struct Bad {
  std::string from, to;  // the edit applied to kGood
  std::size_t line;
  std::string field;
  std::string says;
};

// A key added after tool_length (line 7 of kGood): refused at line 8.
Bad with_key(const std::string& key, const std::string& field, const std::string& says) {
  return Bad{"tool_length: 130.0", "tool_length: 130.0\n" + key, 8, field, says};
}

// The `all` line of axis X's measurement points (line 13) replaced.
Bad x_points_line(const std::string& line, const std::string& field, const std::string& says) {
  return Bad{"      all: [-800.0, -256.0, -478.0]", line, 13, field, says};
}

class MachineRejects : public ::testing::TestWithParam<Bad> {};

TEST_P(MachineRejects, NamesFileLineAndField) {
  const Bad& b = GetParam();
  abbe::testing::expect_machine_rejected(replace(kGood, b.from, b.to), b.line, b.field, b.says);
}

}  // namespace
}  // namespace abbe::machine

namespace abbe::testing {
TEST_P(AppendedKeyRejects, NamesFileLineAndField) {
  const AppendedKey& b = GetParam();
  expect_machine_rejected(kMinimalMachine + b.key, b.line, b.field, b.says);
}
}  // namespace abbe::testing

namespace abbe::machine {
namespace {

INSTANTIATE_TEST_SUITE_P(
    Cases, MachineRejects,
    ::testing::Values(
        Bad{"name: t\n", "", 1, "name", "missing key `name`"},
        Bad{"name: t\n", "name: t\ncolour: red\n", 2, "colour", "unknown key"},
        Bad{"\"w X' b Y Z t\"", "\"w X b Y' Z t\"", 2, "chain", "invalid kinematic chain"},
        Bad{"\"w X' b Y Z t\"", "\"w X b Y t\"", 2, "chain", "invalid kinematic chain"},
        Bad{"\"w X' b Y Z t\"", "[w, b]", 2, "chain", "expected a string"},
        Bad{"x: [-990, 0]", "x: [0, -990]", 4, "travel.x", "below max"},
        Bad{"x: [-990, 0]", "x: [-990, 0, 5]", 4, "travel.x", "list of 2 numbers"},
        Bad{"x: [-990, 0]", "x: [-990, abc]", 4, "travel.x[1]", "not a number"},
        Bad{"  z: [-460, 0]\n", "", 4, "travel.z", "missing key `z`"},
        Bad{"tool_length: 130.0", "tool_length: .nan", 7, "tool_length", "finite"},
        Bad{"tool_length: 130.0", "tool_length: -5", 7, "tool_length", "negative"},
        with_key("tool_table: {T1: 5}", "tool_table.T1", "H number"),
        with_key("tool_diameters: {D2: 5}", "tool_diameters.D2", "not a tool number"),
        with_key("tool_diameters: {2: -5}", "tool_diameters.2",
                 "the tool diameter must not be negative"),
        with_key("tool_diameters: {-1: 5}", "tool_diameters.-1", "must not be negative"),
        with_key("tool_diameters: [5]", "tool_diameters", "mapping"),
        with_key("work_offsets: {G60: [0, 0, 0]}", "work_offsets.G60", "unknown key"),
        with_key("squareness: {EC0X: 1}", "squareness.EC0X", "unknown key"),
        with_key("out_of_range: wrap", "out_of_range", "not one of"),
        Bad{"table: sample-errors.csv", "table: nothere.csv", 8, "table",
            "cannot open the component table"},
        x_points_line("      EXX: [-800.0, -256.0, -478.0]", "axes.X.points.EYX",
                      "no measurement point for EYX"),
        x_points_line("      EXY: [-800.0, -256.0, -478.0]", "axes.X.points.EXY",
                      "belongs to axis Y"),
        x_points_line("      EAX: [-800.0, -256.0, -478.0]", "axes.X.points.EAX", "angular"),
        x_points_line("      all: [-800.0, -256.0]", "axes.X.points.all", "list of 3 numbers"),
        Bad{"{x: -500.0, y: -256.0, z: -280.0, tool_length: 130.0}",
            "{x: -500.0, y: -256.0, z: -280.0}", 11, "axes.X.measured_at.tool_length",
            "missing key"},
        Bad{"  Z:\n    measured_at: {x: -500.0, y: -250.0, z: -300.0, tool_length: 130.0}\n"
            "    points:\n      all: [-500.0, -250.0, -250.0]\n",
            "", 10, "axes.Z", "no measurement record"},
        Bad{"travel:\n  x: [-990, 0]\n  y: [-500, 0]\n  z: [-460, 0]\n", "travel: [1, 2]\n", 3,
            "travel", "must be a mapping"},
        Bad{"name: t", "name: [t", 2, "", "YAML syntax error"}));

}  // namespace
}  // namespace abbe::machine
