// The component table CSV: accepted forms and every rejection with its line,
// column and field.
#include <gtest/gtest.h>

#include "abbe/io/input_error.hpp"
#include "abbe/machine/component_table.hpp"

namespace abbe::machine {
namespace {

const std::string kHeader = "axis,component,position_mm,direction,value\n";

TEST(TableParse, ReadsSeriesPerComponentAndDirection) {
  ComponentTable t = ComponentTable::parse(kHeader +
                                               "X,EXX,-25.0,fwd,1.23\n"
                                               "X,EXX,-25.0,rev,1.50\n"
                                               "X,EXX, 0 ,fwd,+2\r\n"
                                               "\n"
                                               "# comment\n"
                                               "X,EXX,0,rev,-1e-1\n"
                                               "Y,EAY,-25.0,mean,-3.1\n",
                                           "t.csv");
  ASSERT_EQ(t.series().size(), 3u);
  const ComponentSeries* fwd = t.find({Axis::x, 0}, TableDirection::fwd);
  ASSERT_NE(fwd, nullptr);
  EXPECT_EQ(fwd->position_mm, (std::vector<double>{-25.0, 0.0}));
  EXPECT_EQ(fwd->value, (std::vector<double>{1.23, 2.0}));
  EXPECT_EQ(fwd->line, (std::vector<std::size_t>{2, 4}));
  EXPECT_EQ(t.find({Axis::x, 0}, TableDirection::rev)->value.back(), -0.1);
  EXPECT_TRUE(t.bidirectional({Axis::x, 0}));
  EXPECT_TRUE(t.has({Axis::y, 3}));
  EXPECT_FALSE(t.has({Axis::y, 4}));
  EXPECT_TRUE(t.axis_has_components(Axis::y));
  EXPECT_FALSE(t.axis_has_components(Axis::z));
}

TEST(TableParse, AcceptsAllZeroLinearSeries) {
  EXPECT_NO_THROW(ComponentTable::parse(kHeader + "X,EYX,-900,mean,0\nX,EYX,0,mean,0\n", "t"));
}

struct Bad {
  std::string body;  // rows after the header (or the whole text when header is false)
  std::size_t line;
  std::size_t column;  // 0: not checked
  std::string field;
  std::string says;
  bool header = true;
};

class TableRejects : public ::testing::TestWithParam<Bad> {};

TEST_P(TableRejects, NamesLineColumnAndField) {
  const Bad& b = GetParam();
  try {
    ComponentTable::parse(b.header ? kHeader + b.body : b.body, "errors.csv");
    FAIL() << "accepted: " << b.body;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "errors.csv");
    EXPECT_EQ(e.where().line, b.line) << e.what();
    if (b.column) {
      EXPECT_EQ(e.where().column, b.column) << e.what();
    }
    EXPECT_EQ(e.where().field, b.field) << e.what();
    EXPECT_NE(e.message().find(b.says), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, TableRejects,
    ::testing::Values(
        Bad{"axis,comp,position_mm,direction,value\n", 1, 6, "header", "header", false},
        Bad{"", 1, 1, "header", "header", false},
        Bad{"X,EXX,0,mean,1\nW,EXX,1,mean,1\n", 3, 1, "axis", "unknown axis"},
        Bad{"X,EQX,0,mean,1\n", 2, 3, "component", "unknown component"},
        Bad{"X,EXY,0,mean,1\n", 2, 3, "component", "belongs to axis Y"},
        Bad{"Y,EC0Y,0,mean,1\n", 2, 3, "component", "squareness"},
        Bad{"X,EXX,0,mean,1\nX,EXX,-1,mean,1\n", 3, 7, "position_mm", "below"},
        Bad{"X,EXX,0,mean,1\nX,EXX,0,mean,2\n", 3, 7, "position_mm", "duplicate"},
        Bad{"X,EXX,0,mean,nan\n", 2, 14, "value", "finite"},
        Bad{"X,EXX,inf,mean,1\n", 2, 7, "position_mm", "finite"},
        Bad{"X,EXX,0,mean,1.2.3\n", 2, 14, "value", "not a number"},
        Bad{"X,EXX,,mean,1\n", 2, 7, "position_mm", "not a number"},
        Bad{"X,EXX,0,both,1\n", 2, 9, "direction", "not one of"},
        Bad{"X,EXX,0,fwd,1\nX,EXX,0,mean,1\n", 3, 9, "direction", "mixes"},
        Bad{"X,EXX,0,fwd,1\nX,EXX,1,fwd,1\n", 2, 0, "direction", "no `rev`"},
        Bad{"X,EXX,0,mean,1,2\n", 2, 16, "", "more than 5"},
        Bad{"X,EXX,0,mean\n", 2, 13, "value", "4 fields"},
        // Unit checks: mm where µm are expected; angular values out of scale.
        Bad{"X,EXX,-800,mean,0.003\nX,EXX,-400,mean,-0.012\nX,EXX,0,mean,0.004\n", 3, 0, "value",
            "looks like mm"},
        Bad{"Z,EBZ,-400,mean,12\nZ,EBZ,0,mean,25000\n", 3, 0, "value", "implausibly large"}));

TEST(TableParse, UnitCheckNeedsLongTravel) {
  // Small values over a short stroke are plausible (e.g. a 50 mm test axis).
  EXPECT_NO_THROW(ComponentTable::parse(kHeader + "X,EXX,-50,mean,0.01\nX,EXX,0,mean,0.02\n", "t"));
  EXPECT_NO_THROW(ComponentTable::parse(kHeader + "X,EXX,-800,mean,0.06\nX,EXX,0,mean,0.0\n", "t"));
  EXPECT_NO_THROW(ComponentTable::parse(kHeader + "X,EAX,-800,mean,9999\nX,EAX,0,mean,0\n", "t"));
}

}  // namespace
}  // namespace abbe::machine
