// The SDSS plug-plate importer: rows, units, set label, errors.
#include "abbe/io/plugplate.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "abbe/io/input_error.hpp"

namespace abbe::io {
namespace {

const std::string kDir = std::string(ABBE_TEST_DATA_DIR) + "/plugplate/";

TEST(PlugPlate, ReadsBothPlates) {
  const MeasuredData a = load_plugplate(kDir + "D8131_1");
  const MeasuredData b = load_plugplate(kDir + "D8132_1");
  EXPECT_EQ(a.rows.size(), 82u);
  EXPECT_EQ(b.rows.size(), 82u);
  // First hole of 8131: Meas (11.610, −10.090), Nom (11.650, −10.184), Err (−0.039, 0.094).
  EXPECT_DOUBLE_EQ(a.rows[0].p.x(), 11.650);
  EXPECT_DOUBLE_EQ(a.rows[0].p.y(), -10.184);
  EXPECT_DOUBLE_EQ(a.rows[0].p.z(), 0.0);
  EXPECT_DOUBLE_EQ(a.rows[0].d[0], -39.0);
  EXPECT_DOUBLE_EQ(a.rows[0].d[1], 94.0);
  EXPECT_FALSE(a.rows[0].has(2));
  EXPECT_EQ(a.rows[0].set, "8131");
  EXPECT_EQ(b.rows[0].set, "8132");
  EXPECT_EQ(a.rows[0].line, 5u);
}

TEST(PlugPlate, RoundTripsThroughMeasuredDataCsv) {
  const MeasuredData a = load_plugplate(kDir + "D8131_1");
  std::istringstream in(measured_data_to_csv(a));
  const MeasuredData back = read_measured_data(in, "a.csv");
  ASSERT_EQ(back.rows.size(), a.rows.size());
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    EXPECT_NEAR(back.rows[i].p.x(), a.rows[i].p.x(), 1e-9);
    EXPECT_NEAR(back.rows[i].d[1], a.rows[i].d[1], 1e-9);
    EXPECT_EQ(back.rows[i].set, "8131");
  }
}

void expect_error(const std::string& text, std::size_t line, const std::string& field) {
  std::istringstream in(text);
  try {
    read_plugplate(in, "D1");
    FAIL() << "no error for:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "D1");
    EXPECT_EQ(e.where().line, line) << e.what();
    EXPECT_EQ(e.where().field, field) << e.what();
  }
}

TEST(PlugPlate, BadReportsNameLineAndField) {
  const std::string head =
      "Plug Plate: 1\r\nDate: x\r\n\r\n Meas X Meas Y Nom X Nom Y Err X Err Y\r\n";
  expect_error(head + " 1.0 2.0 1.0 2.0 0.0\r\n", 5, "Err Y");
  expect_error(head + " 1.0 2.0 1.0 2.0 0.0 abc\r\n", 5, "Err Y");
  expect_error(head + " 1.0 2.0 1.0 2.0 0.5 0.0\r\n", 5, "Err X");  // Err ≠ Meas − Nom
  expect_error(" 1.0 2.0 1.0 2.0 0.0 0.0\r\n", 1, "header");
  expect_error(head, 4, "");
}

}  // namespace
}  // namespace abbe::io
