// The measured-data reader (DESIGN.md §4): any column order, optional
// columns, empty cells, errors with file, line, column and name.
#include "abbe/io/measured_data.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "abbe/io/input_error.hpp"

namespace abbe::io {
namespace {

MeasuredData read(const std::string& text) {
  std::istringstream in(text);
  return read_measured_data(in, "m.csv");
}

TEST(MeasuredData, AnyColumnOrderAndEmptyCells) {
  const MeasuredData d =
      read("set,dy,z,y,x,t,vx,tool_length\nA,1.5,-3,2,1,10,-1,\nB,0,0,0,0,,,200\n");
  ASSERT_EQ(d.rows.size(), 2u);
  EXPECT_EQ(d.rows[0].p, Eigen::Vector3d(1, 2, -3));
  EXPECT_FALSE(d.rows[0].has(0));
  EXPECT_DOUBLE_EQ(d.rows[0].d[1], 1.5);
  EXPECT_DOUBLE_EQ(d.rows[0].t, 10.0);
  EXPECT_EQ(d.rows[0].v[0], -1);
  EXPECT_NE(d.rows[0].tool_length, d.rows[0].tool_length);  // empty: the machine's default
  EXPECT_EQ(d.rows[0].set, "A");
  EXPECT_FALSE(d.has_column[0]);
  EXPECT_TRUE(d.has_column[1]);
}

TEST(MeasuredData, RowWithoutDeviationIsAnError) {
  EXPECT_THROW(read("x,y,z,dx\n1,2,3,\n"), InputError);
}

TEST(MeasuredData, NormalDeviation) {
  const MeasuredData d = read("x,y,z,nx,ny,nz,dn\n0,0,0,0,0,1,2.5\n");
  EXPECT_TRUE(d.rows[0].has_dn());
  EXPECT_DOUBLE_EQ(d.rows[0].dn, 2.5);
  EXPECT_THROW(read("x,y,z,nx,ny,nz,dn\n0,0,0,0,1,1,2.5\n"), InputError);  // not unit
  EXPECT_THROW(read("x,y,z,dn\n0,0,0,2.5\n"), InputError);                 // no normal
}

TEST(MeasuredData, FilesAsSpreadsheetsSaveThem) {
  // Excel "CSV UTF-8": BOM, upper-case header, CRLF, quoted numbers.
  const MeasuredData a = read("\xEF\xBB\xBFX,Y,Z,DX\r\n\"1.5\",2,3,\"-0.5\"\r\n");
  ASSERT_EQ(a.rows.size(), 1u);
  EXPECT_EQ(a.rows[0].p, Eigen::Vector3d(1.5, 2, 3));
  EXPECT_DOUBLE_EQ(a.rows[0].d[0], -0.5);
  // A German-locale export: `;` separators, decimal commas.
  const MeasuredData b = read("x;y;z;dz;set\n1,5;2;3;0,25;\"A;1\"\n");
  EXPECT_EQ(b.rows[0].p, Eigen::Vector3d(1.5, 2, 3));
  EXPECT_DOUBLE_EQ(b.rows[0].d[2], 0.25);
  EXPECT_EQ(b.rows[0].set, "A;1");
  // Tab-separated, with a comment line.
  const MeasuredData c = read("x\ty\tz\tdy\n# probe 2\n1\t2\t3\t4\n");
  EXPECT_EQ(c.rows[0].line, 3u);
  EXPECT_DOUBLE_EQ(c.rows[0].d[1], 4.0);
}

void expect_error(const std::string& text, std::size_t line, std::size_t column,
                  const std::string& field) {
  try {
    read(text);
    FAIL() << "no error for:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "m.csv");
    EXPECT_EQ(e.where().line, line) << e.what();
    EXPECT_EQ(e.where().column, column) << e.what();
    EXPECT_EQ(e.where().field, field) << e.what();
  }
}

TEST(MeasuredData, ErrorsNameFileLineColumnAndName) {
  expect_error("", 1, 1, "header");
  expect_error("x,y,dx\n", 1, 1, "header");                   // no z
  expect_error("x,y,z\n", 1, 1, "header");                    // no deviation column
  expect_error("x,y,z,dx,x\n", 1, 10, "x");                   // twice
  expect_error("x,y,z,dx\n1,2,3,4\n1,2,abc,4\n", 3, 5, "z");  // not a number
  expect_error("x,y,z,dx\n1,,3,4\n", 2, 3, "y");              // empty coordinate
  expect_error("x,y,z,dx,vy\n1,2,3,4,2\n", 2, 9, "vy");       // direction not −1/0/1
  expect_error("x,y,z,dx\n1,2,3\n", 2, 6, "dx");              // missing field
  expect_error("x,y,z,dx\n1,2,3,inf\n", 2, 7, "dx");
}

}  // namespace
}  // namespace abbe::io
