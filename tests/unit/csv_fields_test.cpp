// io::trim_blanks, which io::CsvReader (csv_reader_test.cpp) uses for blank
// lines and fields.
#include "abbe/io/csv_fields.hpp"

#include <gtest/gtest.h>

namespace abbe::io {
namespace {

TEST(CsvFields, TrimRemovesBlanksAndTheCrOfCrlf) {
  EXPECT_EQ(trim_blanks(" \t1.5 \t\r"), "1.5");
  EXPECT_EQ(trim_blanks("\r"), "");
  EXPECT_EQ(trim_blanks("a b"), "a b");
  EXPECT_EQ(trim_blanks("\ra"), "\ra");  // a leading CR is content, not a line ending
}

}  // namespace
}  // namespace abbe::io
