// io::split_csv_line / io::trim_blanks: the field columns every CSV reader
// puts into its file:line:col errors.
#include "abbe/io/csv_fields.hpp"

#include <gtest/gtest.h>

namespace abbe::io {
namespace {

TEST(CsvFields, FieldsKeepTheirOneBasedStartColumns) {
  const auto f = split_csv_line("x, y ,,z\r");
  ASSERT_EQ(f.size(), 4U);
  EXPECT_EQ(f[0].text, "x");
  EXPECT_EQ(f[0].column, 1U);
  EXPECT_EQ(f[1].text, " y ");
  EXPECT_EQ(f[1].column, 3U);
  EXPECT_EQ(f[2].text, "");
  EXPECT_EQ(f[2].column, 7U);
  EXPECT_EQ(f[3].text, "z\r");
  EXPECT_EQ(f[3].column, 8U);
}

TEST(CsvFields, EmptyLineIsOneEmptyField) {
  const auto f = split_csv_line("");
  ASSERT_EQ(f.size(), 1U);
  EXPECT_EQ(f[0].text, "");
  EXPECT_EQ(f[0].column, 1U);
}

TEST(CsvFields, TrimRemovesBlanksAndTheCrOfCrlf) {
  EXPECT_EQ(trim_blanks(" \t1.5 \t\r"), "1.5");
  EXPECT_EQ(trim_blanks("\r"), "");
  EXPECT_EQ(trim_blanks("a b"), "a b");
  EXPECT_EQ(trim_blanks("\ra"), "\ra");  // a leading CR is content, not a line ending
}

}  // namespace
}  // namespace abbe::io
