// CsvReader (src/io/csv_reader.cpp): CSV files as people save them.
#include "abbe/io/csv_reader.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "abbe/io/input_error.hpp"

using abbe::InputError;
using abbe::io::CsvReader;

namespace {

// Every record after the header, as field texts.
std::vector<std::vector<std::string>> rows(CsvReader& r) {
  std::vector<std::vector<std::string>> out;
  while (r.next()) {
    out.emplace_back();
    for (const auto& f : r.fields()) out.back().emplace_back(f.text);
  }
  return out;
}

std::string error_of(const std::string& text, bool header_only = false) {
  std::istringstream in(text);
  CsvReader r(in, "f.csv");
  try {
    r.read_header();
    if (!header_only)
      while (r.next()) {
        for (const auto& f : r.fields()) (void)r.number(f, "v");
      }
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(CsvReader, PlainCommaFile) {
  std::istringstream in("x,y,z\n1,2,3\n4,5,6\n");
  CsvReader r(in, "p.csv");
  r.read_header();
  EXPECT_EQ(r.separator(), ',');
  EXPECT_EQ(r.header_names(), (std::vector<std::string>{"x", "y", "z"}));
  EXPECT_EQ(rows(r), (std::vector<std::vector<std::string>>{{"1", "2", "3"}, {"4", "5", "6"}}));
}

TEST(CsvReader, ExcelFileWithBomCrlfAndUpperCaseHeader) {
  std::istringstream in("\xEF\xBB\xBFX,Y,Z\r\n1,2,3\r\n");
  CsvReader r(in, "excel.csv");
  r.read_header();
  ASSERT_TRUE(r.column("x"));
  EXPECT_EQ(*r.column("x"), 0u);
  EXPECT_EQ(*r.column("Z"), 2u);
  EXPECT_FALSE(r.column("dx"));
  ASSERT_TRUE(r.next());
  EXPECT_EQ(r.fields()[2].text, "3");  // no CR
  EXPECT_EQ(r.line(), 2u);
}

TEST(CsvReader, SemicolonFileWithDecimalCommas) {
  std::istringstream in("x;y;z;set\n1,5;-2,25e-1;3;A,B\n");
  CsvReader r(in, "de.csv");
  r.read_header();
  EXPECT_EQ(r.separator(), ';');
  ASSERT_TRUE(r.next());
  EXPECT_EQ(*r.number(r.fields()[0], "x"), 1.5);
  EXPECT_EQ(*r.number(r.fields()[1], "y"), -0.225);
  EXPECT_EQ(r.fields()[3].text, "A,B");  // not a number: kept as written
}

TEST(CsvReader, TabFile) {
  std::istringstream in("x\ty\tz\n 1\t2 \t3\n");
  CsvReader r(in, "t.tsv");
  r.read_header();
  EXPECT_EQ(r.separator(), '\t');
  EXPECT_EQ(rows(r), (std::vector<std::vector<std::string>>{{"1", "2", "3"}}));
}

TEST(CsvReader, QuotedFields) {
  std::istringstream in("\"x\",\"y\",name\n\"1.5\", \"2\" ,\"a, \"\"b\"\"\"\n");
  CsvReader r(in, "q.csv");
  r.read_header();
  EXPECT_EQ(r.header_names(), (std::vector<std::string>{"x", "y", "name"}));
  ASSERT_TRUE(r.next());
  EXPECT_EQ(*r.number(r.fields()[0], "x"), 1.5);
  EXPECT_EQ(r.fields()[1].text, "2");
  EXPECT_EQ(r.fields()[1].column, 8u);  // the opening quote
  EXPECT_EQ(r.fields()[2].text, "a, \"b\"");
}

TEST(CsvReader, QuotedLineBreakKeepsLineNumbers) {
  std::istringstream in("x,note\n1,\"two\nlines\"\n2,x\n");
  CsvReader r(in, "n.csv");
  r.read_header();
  ASSERT_TRUE(r.next());
  EXPECT_EQ(r.fields()[1].text, "two\nlines");
  EXPECT_EQ(r.line(), 2u);
  ASSERT_TRUE(r.next());
  EXPECT_EQ(r.line(), 4u);
}

TEST(CsvReader, BlankAndCommentLinesAreSkipped) {
  std::istringstream in("\n\nx\n\n# a comment\n1\n");
  CsvReader r(in, "c.csv", CsvReader::Options{'#'});
  r.read_header();
  ASSERT_TRUE(r.next());
  EXPECT_EQ(r.line(), 6u);
  EXPECT_FALSE(r.next());
}

TEST(CsvReader, ErrorsNameFileLineAndColumn) {
  EXPECT_NE(
      error_of("x,y\n1,2\n3,abc\n").find("f.csv:3:3 [v]: error: \"abc\" is not a finite number"),
      std::string::npos);
  EXPECT_NE(error_of("x,y\n1,\"2\n").find("f.csv:2:3: error: a quoted field is not closed"),
            std::string::npos);
  EXPECT_NE(
      error_of("x,y\n\"1\"2,3\n").find("f.csv:2:4: error: unexpected text after the closing quote"),
      std::string::npos);
  EXPECT_NE(error_of("").find("f.csv:1:1 [header]: error: empty file"), std::string::npos);
  EXPECT_NE(error_of("x,X\n", true).find("f.csv:1:3 [x]: error: column `x` appears twice"),
            std::string::npos);
}

TEST(CsvReader, ShortRecordNamesTheMissingColumn) {
  std::istringstream in("x,y,z\n1,2\n");
  CsvReader r(in, "s.csv");
  r.read_header();
  ASSERT_TRUE(r.next());
  try {
    (void)r.field(2, "z");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("s.csv:2:4 [z]: error: 2 fields, but `z` is column 3"),
              std::string::npos)
        << e.what();
  }
}

TEST(CsvReader, NumbersAreStrict) {
  using abbe::io::parse_csv_number;
  EXPECT_EQ(*parse_csv_number("+1e3"), 1000.0);
  EXPECT_EQ(*parse_csv_number("-0.5"), -0.5);
  EXPECT_FALSE(parse_csv_number("1.5mm"));
  EXPECT_FALSE(parse_csv_number("nan"));
  EXPECT_FALSE(parse_csv_number("inf"));
  EXPECT_FALSE(parse_csv_number(""));
  EXPECT_FALSE(parse_csv_number("1,5"));  // decimal commas only in ; or tab files
}
