// How the compensator writes a corrected number: in the style of the number
// it replaces, with up to max_decimals places, and — for the Fanuc dialect —
// always with a decimal point. Expected strings are written by hand.
#include <gtest/gtest.h>

#include "abbe/compensate/number_format.hpp"

namespace abbe::compensate {
namespace {

TEST(NumberFormat, StyleOfTheWrittenNumber) {
  const NumberStyle a = number_style("-12.50");
  EXPECT_EQ(a.decimals, 2);
  EXPECT_TRUE(a.leading_zero);
  EXPECT_FALSE(a.plus_sign);
  const NumberStyle b = number_style("+.5");
  EXPECT_EQ(b.decimals, 1);
  EXPECT_FALSE(b.leading_zero);
  EXPECT_TRUE(b.plus_sign);
  EXPECT_EQ(number_style("100").decimals, 0);
}

TEST(NumberFormat, KeepsOwnDecimalsAndDropsOtherTrailingZeros) {
  EXPECT_EQ(format_number(12.5, number_style("12.50"), 4), "12.50");
  EXPECT_EQ(format_number(12.50123, number_style("12.50"), 4), "12.5012");
  EXPECT_EQ(format_number(10.0, number_style("10"), 4), "10");
  EXPECT_EQ(format_number(10.00004, number_style("10"), 4), "10");
  EXPECT_EQ(format_number(10.00006, number_style("10"), 4), "10.0001");
  EXPECT_EQ(format_number(0.25, number_style(".5"), 4), ".25");
  EXPECT_EQ(format_number(-0.00001, number_style("0"), 4), "0");  // no negative zero
  EXPECT_EQ(format_number(1.5, number_style("+1"), 4), "+1.5");
}

TEST(NumberFormat, PointAlwaysForFanuc) {
  NumberStyle s = number_style("100");
  s.point_always = true;
  EXPECT_EQ(format_number(100.0, s, 4), "100.");
  EXPECT_EQ(format_number(-5.0, s, 4), "-5.");
  EXPECT_EQ(format_number(0.0, s, 4), "0.");
  EXPECT_EQ(format_number(0.1234, s, 4), "0.1234");
  NumberStyle fresh;
  fresh.point_always = true;
  EXPECT_EQ(format_number(5.0, fresh, 4), "5.");
  // The slow path (more digits than a 64-bit integer holds) keeps the point too.
  EXPECT_EQ(format_number(1e17, fresh, 4), "100000000000000000.");
}

TEST(NumberFormat, RoundTo) {
  EXPECT_DOUBLE_EQ(round_to(1.23456, 4), 1.2346);
  EXPECT_DOUBLE_EQ(round_to(-1.23454, 4), -1.2345);
  EXPECT_DOUBLE_EQ(round_to(2.5, 0), 3.0);
}

}  // namespace
}  // namespace abbe::compensate
