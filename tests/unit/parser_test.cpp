// The line parser on its own: accepted forms, byte offsets, refusals with
// their columns, and the streaming BlockReader.
#include "abbe/gcode/parser.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "abbe/io/input_error.hpp"
#include "text_block_reader.hpp"

namespace {

using abbe::InputError;
using abbe::gcode::Block;
using abbe::gcode::BlockReader;
using abbe::gcode::parse_line;
using abbe::gcode::Word;
using abbe::gcode::testing::TextBlockReader;

Block parse(std::string_view line) { return parse_line(line, 7, "t.nc"); }

// The error for a line that must be refused.
InputError refusal(std::string_view line) {
  try {
    parse(line);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted: '" << line << "'";
  return InputError({}, "");
}

// Replacing every word's number by the text of itself must give the line
// back byte for byte; replacing it by a marker must change only that number.
void expect_offsets_round_trip(const std::string& line) {
  const Block b = parse(line);
  std::vector<Word> words = b.words;
  if (b.n) words.push_back(*b.n);
  for (const Word& w : words) {
    ASSERT_LE(w.begin, w.number_begin);
    ASSERT_LT(w.number_begin, w.end);
    ASSERT_LE(w.end, line.size());
    EXPECT_EQ(std::toupper(static_cast<unsigned char>(line[w.begin])), w.letter);
    std::string copy = line;
    copy.replace(w.number_begin, w.end - w.number_begin, "#");
    // Parsing the number text alone as a word must give the same value.
    const std::string text = line.substr(w.number_begin, w.end - w.number_begin);
    const Block alone = parse("X" + text);
    ASSERT_EQ(alone.words.size(), 1U);
    EXPECT_EQ(alone.words[0].value, w.value) << text;
    EXPECT_EQ(copy.substr(0, w.number_begin), line.substr(0, w.number_begin));
    EXPECT_EQ(copy.substr(w.number_begin + 1), line.substr(w.end));
  }
  // Rebuild the line from the pieces between numbers and the numbers themselves.
  std::string rebuilt;
  std::size_t at = 0;
  std::sort(words.begin(), words.end(),
            [](const Word& a, const Word& c) { return a.number_begin < c.number_begin; });
  for (const Word& w : words) {
    rebuilt += line.substr(at, w.number_begin - at);
    rebuilt += line.substr(w.number_begin, w.end - w.number_begin);
    at = w.end;
  }
  rebuilt += line.substr(at);
  EXPECT_EQ(rebuilt, line);
}

TEST(Parser, WordsInEveryFormCamPostsEmit) {
  const Block b = parse("G1 X10 Y-.5 Z1. F+100 I-0.25 J.75");
  ASSERT_EQ(b.words.size(), 7U);
  const char letters[] = {'G', 'X', 'Y', 'Z', 'F', 'I', 'J'};
  const double values[] = {1, 10, -0.5, 1, 100, -0.25, 0.75};
  for (std::size_t i = 0; i < 7; ++i) {
    EXPECT_EQ(b.words[i].letter, letters[i]);
    EXPECT_DOUBLE_EQ(b.words[i].value, values[i]) << i;
  }
  EXPECT_FALSE(b.n);
  EXPECT_FALSE(b.block_delete);
  EXPECT_TRUE(b.comments.empty());
  EXPECT_EQ(b.line, 7U);
}

TEST(Parser, WordsWithoutBlanksBetweenThem) {
  const Block b = parse("G01X-1.5Y2Z.5");
  ASSERT_EQ(b.words.size(), 4U);
  EXPECT_EQ(b.words[0].value, 1.0);
  EXPECT_EQ(b.words[1].value, -1.5);
  EXPECT_EQ(b.words[2].value, 2.0);
  EXPECT_EQ(b.words[3].value, 0.5);
}

TEST(Parser, BlanksBetweenLetterSignAndDigits) {
  const Block b = parse("x 10 y - 2.5\tz\t-\t3");
  ASSERT_EQ(b.words.size(), 3U);
  EXPECT_EQ(b.words[0].letter, 'X');
  EXPECT_EQ(b.words[0].value, 10.0);
  EXPECT_EQ(b.words[1].value, -2.5);
  EXPECT_EQ(b.words[2].value, -3.0);
  // The number starts at the sign, not at the digits.
  EXPECT_EQ(b.words[1].begin, 5U);
  EXPECT_EQ(b.words[1].number_begin, 7U);
  EXPECT_EQ(b.words[1].end, 12U);
}

TEST(Parser, LowerCaseLettersAreUpperCased) {
  const Block b = parse("n5 g2 x1 y2 i0.5 j0 f300");
  ASSERT_TRUE(b.n);
  EXPECT_EQ(b.n->letter, 'N');
  EXPECT_EQ(b.n->value, 5.0);
  std::string letters;
  for (const Word& w : b.words) letters += w.letter;
  EXPECT_EQ(letters, "GXYIJF");
}

TEST(Parser, OffsetsOfWords) {
  const std::string line = "N010 G1 X-12.5 (c) y 3";
  const Block b = parse(line);
  ASSERT_TRUE(b.n);
  EXPECT_EQ(b.n->begin, 0U);
  EXPECT_EQ(b.n->number_begin, 1U);
  EXPECT_EQ(b.n->end, 4U);
  ASSERT_EQ(b.words.size(), 3U);
  EXPECT_EQ(b.words[1].begin, 8U);
  EXPECT_EQ(b.words[1].number_begin, 9U);
  EXPECT_EQ(b.words[1].end, 14U);
  EXPECT_EQ(line.substr(b.words[1].number_begin, b.words[1].end - b.words[1].number_begin),
            "-12.5");
  EXPECT_EQ(b.words[2].begin, 19U);
  EXPECT_EQ(b.words[2].number_begin, 21U);
  EXPECT_EQ(b.words[2].end, 22U);
}

TEST(Parser, OffsetsRoundTripByteForByte) {
  for (const std::string line :
       {"G1 X10 Y-.5 Z1. F+100", "N10 G01X-1.5Y2Z.5 (move) ; done", "/ n20 x - 1 y+ 2 *33",
        "\tG2 X1. Y2. I.5 J-0.5 F1200.0", "G0 Z 5   ", "M3 S12000 (spindle (on) no)"}) {
    if (line == "M3 S12000 (spindle (on) no)") continue;  // nested: refused, tested below
    SCOPED_TRACE(line);
    expect_offsets_round_trip(line);
  }
}

TEST(Parser, CommentsAnywhereBetweenWords) {
  const std::string line = "G1 (first) X1 (second: ünïcödé) Y2 ; tail (with parens)";
  const Block b = parse(line);
  ASSERT_EQ(b.words.size(), 3U);
  ASSERT_EQ(b.comments.size(), 3U);
  EXPECT_EQ(b.comments[0].text, "first");
  EXPECT_EQ(b.comments[0].begin, 3U);
  EXPECT_EQ(b.comments[0].end, 10U);
  EXPECT_EQ(line.substr(b.comments[0].begin, b.comments[0].end - b.comments[0].begin), "(first)");
  EXPECT_EQ(b.comments[1].text, "second: ünïcödé");
  EXPECT_EQ(b.comments[2].text, " tail (with parens)");
  EXPECT_EQ(line[b.comments[2].begin], ';');
  EXPECT_EQ(b.comments[2].end, line.size());
}

TEST(Parser, EmptyAndBlankAndCommentOnlyLines) {
  for (const char* line : {"", "   ", "\t", "(only a comment)", "; semicolon", "  ()  "}) {
    const Block b = parse(line);
    EXPECT_TRUE(b.words.empty()) << line;
    EXPECT_FALSE(b.n);
    EXPECT_FALSE(b.percent);
  }
}

TEST(Parser, BlockDelete) {
  const Block b = parse("  /N10 G0 X1");
  EXPECT_TRUE(b.block_delete);
  ASSERT_TRUE(b.n);
  EXPECT_EQ(b.n->value, 10.0);
  ASSERT_EQ(b.words.size(), 2U);
  EXPECT_TRUE(parse("/ G0 X1").block_delete);
  EXPECT_FALSE(parse("G0 X1").block_delete);
}

TEST(Parser, PercentLines) {
  EXPECT_TRUE(parse("%").percent);
  const Block b = parse(" % (program name)");
  EXPECT_TRUE(b.percent);
  ASSERT_EQ(b.comments.size(), 1U);
  EXPECT_EQ(b.comments[0].text, "program name");
  EXPECT_TRUE(b.words.empty());
}

TEST(Parser, ProgramNumberLines) {
  Block b = parse("O1234");
  ASSERT_TRUE(b.program_number);
  EXPECT_EQ(*b.program_number, 1234);
  b = parse("o0042 (FACE MILL)");
  ASSERT_TRUE(b.program_number);
  EXPECT_EQ(*b.program_number, 42);
  ASSERT_EQ(b.comments.size(), 1U);
  EXPECT_EQ(b.comments[0].text, "FACE MILL");
  EXPECT_FALSE(parse("G0 X1").program_number);
}

TEST(Parser, Checksum) {
  const Block b = parse("N3 G1 X1 *57");
  ASSERT_TRUE(b.checksum);
  EXPECT_EQ(*b.checksum, 57);
  ASSERT_EQ(b.words.size(), 2U);
  EXPECT_FALSE(parse("G1 X1").checksum);
}

TEST(Parser, TrailingCarriageReturnIsIgnored) {
  const Block b = parse("G1 X1 (c)\r");
  ASSERT_EQ(b.words.size(), 2U);
  ASSERT_EQ(b.comments.size(), 1U);
  EXPECT_EQ(b.comments[0].text, "c");
  EXPECT_TRUE(parse("\r").words.empty());
}

TEST(Parser, NumbersAreExact) {
  EXPECT_EQ(parse("X0.1").words[0].value, 0.1);
  EXPECT_EQ(parse("X-123456.789012").words[0].value, -123456.789012);
  EXPECT_EQ(parse("X000.5000").words[0].value, 0.5);
  EXPECT_EQ(parse("X-0").words[0].value, 0.0);
  // 64 significant characters are still accepted.
  EXPECT_EQ(parse("X" + std::string(63, '0') + "1").words[0].value, 1.0);
}

// A random decimal text: a sign or none, 0-21 digits before the point and
// 0-25 after it (at least one digit in all).
std::string random_decimal(std::mt19937_64& rng) {
  std::string text = (rng() % 2) ? "-" : "";
  const int n_int = static_cast<int>(rng() % 22);
  const int n_frac = static_cast<int>(rng() % 26);
  for (int k = 0; k < n_int; ++k) text += static_cast<char>('0' + rng() % 10);
  if (n_frac > 0 || n_int == 0) text += '.';
  for (int k = 0; k < std::max(n_frac, n_int == 0 ? 1 : 0); ++k)
    text += static_cast<char>('0' + rng() % 10);
  return text;
}

TEST(Parser, NumbersConvertLikeStrtod) {
  // Random decimal texts of every length, with and without fraction; the
  // parser's value must be the correctly rounded double strtod gives.
  std::mt19937_64 rng(42);
  for (int i = 0; i < 20000; ++i) {
    const std::string text = random_decimal(rng);
    const Block b = parse("X" + text);
    ASSERT_EQ(b.words.size(), 1U) << text;
    EXPECT_EQ(b.words[0].value, std::strtod(text.c_str(), nullptr)) << text;
  }
}

TEST(Parser, NumbersConvertLikeStrtodInsideALine) {
  // Numbers of every length followed by more of the line, several in one
  // line, must convert as alone.
  std::mt19937_64 rng(7);
  for (int i = 0; i < 20000; ++i) {
    std::string line;
    std::vector<std::string> texts;
    for (int w = 0; w < 3; ++w) {
      const std::string text = random_decimal(rng);
      line += std::string(1, "XYZ"[w]) + text + (rng() % 2 ? " " : "");
      texts.push_back(text);
    }
    line += "(a comment after the numbers)";
    const Block b = parse(line);
    ASSERT_EQ(b.words.size(), 3U) << line;
    for (std::size_t w = 0; w < 3; ++w)
      EXPECT_EQ(b.words[w].value, std::strtod(texts[w].c_str(), nullptr)) << line;
  }
}

TEST(Parser, ANumberEndsAtTheFirstByteThatIsNotADigit) {
  // Every byte value after "12": a digit continues the number, '.' starts
  // the fraction, anything else ends it (or the line is refused).
  for (int c = 0; c < 256; ++c) {
    const std::string line = "X12" + std::string(1, static_cast<char>(c)) + "45678901 Y2";
    double value = 0.0;
    try {
      const Block b = parse(line);
      ASSERT_FALSE(b.words.empty());
      value = b.words[0].value;
    } catch (const InputError&) {
      EXPECT_FALSE(c >= '0' && c <= '9') << c;
      EXPECT_NE(c, '.');
      continue;
    }
    if (c >= '0' && c <= '9')
      EXPECT_EQ(value, std::strtod(line.substr(1, 11).c_str(), nullptr)) << c;
    else if (c == '.')
      EXPECT_EQ(value, 12.45678901);
    else
      EXPECT_EQ(value, 12.0) << c;
  }
}

// Message and 1-based column of the refusal of `line`.
void expect_refused(const std::string& line, std::size_t column, const std::string& message) {
  SCOPED_TRACE(line);
  const InputError e = refusal(line);
  EXPECT_EQ(e.where().file, "t.nc");
  EXPECT_EQ(e.where().line, 7U);
  EXPECT_EQ(e.where().column, column);
  EXPECT_NE(e.message().find(message), std::string::npos) << e.message();
  EXPECT_EQ(e.where().source_line, line.back() == '\r' ? line.substr(0, line.size() - 1) : line);
}

// The refusals checked by the ParserRefuses tests, each under the name of its
// test: the line, the 1-based column and words of the message.
struct Refusal {
  std::string test;
  std::string line;
  std::size_t column;
  std::string message;
};
const std::vector<Refusal> kRefusals = {
    {"Parameters", "G1 #1", 4, "bad parameter setting (#n = value or #<name> = value)"},
    {"Parameters", "G1 X#", 5, "bad parameter in word 'X'"},
    {"Parameters", "#<name>3", 1, "bad parameter setting"},
    {"Parameters", "G1 X#<a", 5, "bad parameter in word 'X'"},
    {"Expressions", "G1 X[1+]", 5, "bad expression in word 'X'"},
    {"Expressions", "G1 [1]", 4, "an expression ([...]) must be the value of a word"},
    {"Expressions", "G1 X - [1", 8, "bad expression in word 'X'"},
    {"Expressions", "G1 X[1 FOO 2]", 5, "bad expression in word 'X'"},
    {"OWordControlFlow", "  o<drill> foo [1]", 3, "bad O-word: o<name> must be followed by sub"},
    {"OWordControlFlow", "o100 sub X1", 10, "bad O-word line: only [...] arguments and a comment"},
    {"OWordControlFlow", "G0 O100", 4, "an O-word must be the first word of its line"},
    {"OWordControlFlow", "O1 G0 X1", 4, "a program number line (O...) may carry only a comment"},
    {"OWordControlFlow", "O", 1, "word 'O' has no number"},
    {"Comments", "G1 (abc", 4, "unclosed comment"},
    {"Comments", "G1 X1 (a (b) c)", 10, "nested comments are not supported"},
    {"Comments", "G1 X1 )", 7, "')' without a matching '('"},
    {"LetterWithoutNumber", "G1 X", 4, "word 'X' has no number"},
    {"LetterWithoutNumber", "G1 X Y1", 4, "word 'X' has no number"},
    {"LetterWithoutNumber", "g1 y (c) 1", 4, "word 'Y' has no number"},
    {"LetterWithoutNumber", "G1 X-", 4, "word 'X' has no number"},
    {"BadNumbers", "G1 X1.2.3", 5, "bad number '1.2.3' in word 'X'"},
    {"BadNumbers", "G1 X.", 5, "bad number '.' in word 'X'"},
    {"BadNumbers", "G1 X1e5", 5, "exponents are not supported"},
    {"BadNumbers", "G1 X1.5E-3", 5, "exponents are not supported"},
    {"BadNumbers", "G1 X1 0", 7, "a blank inside a number is not supported"},
    {"BadNumbers", "10", 1, "number '10' without a word letter"},
    {"BadNumbers", "G1 (c) -2", 8, "number '-2' without a word letter"},
    {"BadNumbers", "G1 10", 4, "a blank inside a number is not supported"},
    {"NanInfinityAndHugeNumbers", "G1 XNAN", 5, "NaN and infinity are not numbers"},
    {"NanInfinityAndHugeNumbers", "G1 X-inf", 6, "NaN and infinity are not numbers"},
    {"NanInfinityAndHugeNumbers", "G1 X" + std::string(65, '9'), 5, "number is too long"},
    {"NanInfinityAndHugeNumbers", "G1 X1" + std::string(400, '0') + ".0", 5, "number is too long"},
    {"NanInfinityAndHugeNumbers", "O" + std::string(30, '9'), 2, "program number is too large"},
    {"LettersAbbeDoesNotRead", "G1 U10", 4, "axis word 'U' is not supported (3-axis machine)"},
    {"MisplacedStructure", "G1 N10 X1", 4, "a line number (N) must be the first word"},
    {"MisplacedStructure", "N1.5 G1", 2, "bad line number"},
    {"MisplacedStructure", "G1 / X1", 4, "block delete '/' must be the first character"},
    {"MisplacedStructure", "% G1", 3, "only a comment may follow '%'"},
    {"MisplacedStructure", "G1 %", 4, "'%' (tape delimiter) must stand alone"},
    {"MisplacedStructure", "G1 X1 *12 Y2", 11, "the checksum (*nn) must be the last thing"},
    {"MisplacedStructure", "G1 X1 *", 7, "bad checksum"},
    {"BinaryBytesOutsideComments", std::string("G1 X1 \x01", 7), 7, "unexpected byte 0x01"},
    {"BinaryBytesOutsideComments", std::string("G1\0X1", 5), 3, "unexpected byte 0x00"},
    {"BinaryBytesOutsideComments", "G1 X1 \xc3\xa9", 7, "unexpected byte 0xc3"},
    {"BinaryBytesOutsideComments", "G1\rX1", 3, "carriage return inside a line"},
    {"BinaryBytesOutsideComments", "G1 X1 !", 7, "unexpected character '!'"},
};

// Every refusal of kRefusals listed under `test` (there is at least one).
void expect_refusals_of(const std::string& test) {
  std::size_t rows = 0;
  for (const Refusal& r : kRefusals) {
    if (r.test != test) continue;
    expect_refused(r.line, r.column, r.message);
    ++rows;
  }
  EXPECT_GT(rows, 0U) << test;
}

TEST(ParserRefuses, Parameters) { expect_refusals_of("Parameters"); }

TEST(ParserRefuses, Expressions) { expect_refusals_of("Expressions"); }

TEST(ParserRefuses, OWordControlFlow) { expect_refusals_of("OWordControlFlow"); }

TEST(ParserRefuses, Comments) { expect_refusals_of("Comments"); }

TEST(ParserRefuses, LetterWithoutNumber) { expect_refusals_of("LetterWithoutNumber"); }

TEST(ParserRefuses, BadNumbers) { expect_refusals_of("BadNumbers"); }

TEST(ParserRefuses, NanInfinityAndHugeNumbers) { expect_refusals_of("NanInfinityAndHugeNumbers"); }

TEST(ParserRefuses, LettersAbbeDoesNotRead) {
  expect_refusals_of("LettersAbbeDoesNotRead");
  // A B C (rotary axes) are read: the interpreter accepts a rotary word
  // that never moves and refuses one that does (interpreter_test.cpp).
  for (const char* axis : {"U", "V", "W", "u"}) {
    const std::string line = std::string("G0 ") + axis + "1";
    const char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(axis[0])));
    expect_refused(line, 4, std::string("axis word '") + upper + "'");
  }
  // Polar words are read (rs274ngc's @ radius and ^ angle); a polar word
  // needs a number like every other word.
  const Block polar = parse("G1 @1.5 ^-90");
  ASSERT_EQ(polar.words.size(), 3u);
  EXPECT_EQ(polar.words[1].letter, '@');
  EXPECT_DOUBLE_EQ(polar.words[1].value, 1.5);
  EXPECT_EQ(polar.words[2].letter, '^');
  EXPECT_DOUBLE_EQ(polar.words[2].value, -90.0);
  expect_refused("G1 @ ^90", 4, "word '@' has no number");
}

TEST(Parser, OWordLineWithSeveralComments) {
  // rs274ngc allows more than one comment after an O-word's arguments
  // (LinuxCNC's daisy.ngc: "O200 call [1] [#107] (Dai-)  (G)").
  const Block b = parse("O200 call [1]     [2] (Dai-)  (G)");
  EXPECT_EQ(b.o.keyword, abbe::gcode::OKeyword::call);
  EXPECT_EQ(b.o.args.size(), 2u);
}

TEST(ParserRefuses, MisplacedStructure) { expect_refusals_of("MisplacedStructure"); }

TEST(ParserRefuses, BinaryBytesOutsideComments) {
  expect_refusals_of("BinaryBytesOutsideComments");
  // Inside a comment every byte but parentheses is fine.
  EXPECT_EQ(parse(std::string("(\x01\x7f\xff\0)", 6)).comments.size(), 1U);
}

TEST(ParserRefuses, ErrorTextNamesFileLineColumnAndShowsCaret) {
  const InputError e = refusal("G1 X1.2.3");
  const std::string what = e.what();
  EXPECT_EQ(what.rfind("t.nc:7:5: error: bad number '1.2.3' in word 'X'", 0), 0U) << what;
  EXPECT_NE(what.find("G1 X1.2.3\n      ^"), std::string::npos) << what;
}

TEST(ParserLimits, TenMegabyteLineOfWordsIsRefusedQuickly) {
  std::string line;
  line.reserve(10 << 20);
  while (line.size() < (10U << 20)) line += "X1 ";
  const InputError e = refusal(line);
  EXPECT_NE(e.message().find("too many words in one block"), std::string::npos) << e.message();
  EXPECT_EQ(e.where().column, 1024U * 3U + 1U);
}

TEST(ParserLimits, TenMegabyteCommentIsAccepted) {
  const std::string line = "G0 X1 (" + std::string(10 << 20, 'c') + ") Y2";
  const Block b = parse(line);
  ASSERT_EQ(b.comments.size(), 1U);
  EXPECT_EQ(b.comments[0].text.size(), 10U << 20);
  ASSERT_EQ(b.words.size(), 3U);
  EXPECT_EQ(b.words[2].number_begin, line.size() - 1);
}

TEST(ParserLimits, TenMegabyteNumberIsRefused) {
  const std::string line = "G0 X" + std::string(10 << 20, '1');
  EXPECT_NE(refusal(line).message().find("number is too long"), std::string::npos);
}

TEST(ParserLimits, ThousandWordsAreAccepted) {
  std::string line;
  for (int i = 0; i < 1000; ++i) line += "M" + std::to_string(i % 100) + " ";
  EXPECT_EQ(parse(line).words.size(), 1000U);
}

TEST(BlockReader, ReadsLfCrlfAndALastLineWithoutTerminator) {
  std::istringstream in("%\r\nG0 X1\nG1 Y2 (c)\r\n\nM30");
  BlockReader reader(in, "prog.nc");
  Block b;
  std::vector<std::string> raw;
  std::vector<std::string> endings;
  std::vector<std::size_t> words;
  while (reader.next(b)) {
    EXPECT_EQ(b.line, reader.line_number());
    raw.push_back(reader.raw_line());
    endings.push_back(reader.line_ending());
    words.push_back(b.words.size());
  }
  EXPECT_EQ(raw, (std::vector<std::string>{"%", "G0 X1", "G1 Y2 (c)", "", "M30"}));
  EXPECT_EQ(endings, (std::vector<std::string>{"\r\n", "\n", "\r\n", "\n", ""}));
  EXPECT_EQ(words, (std::vector<std::size_t>{0, 2, 2, 0, 1}));
  EXPECT_EQ(reader.file(), "prog.nc");
}

TEST(BlockReader, Utf8ByteOrderMarkIsSkippedOnlyAtTheStart) {
  std::istringstream in("\xEF\xBB\xBFG0 X1\n\xEF\xBB\xBFG0 X2\n");
  BlockReader reader(in, "bom.nc");
  Block b;
  ASSERT_TRUE(reader.next(b));
  EXPECT_TRUE(reader.byte_order_mark());
  EXPECT_EQ(reader.raw_line(), "G0 X1");
  ASSERT_EQ(b.words.size(), 2U);
  EXPECT_EQ(b.words[1].number_begin, 4U);
  try {
    reader.next(b);
    FAIL() << "a byte order mark inside the file was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(e.message().find("unexpected byte 0xef"), std::string::npos) << e.message();
    EXPECT_EQ(e.where().line, 2U);
  }
  std::istringstream plain("G0 X1\n");
  BlockReader plain_reader(plain, "plain.nc");
  ASSERT_TRUE(plain_reader.next(b));
  EXPECT_FALSE(plain_reader.byte_order_mark());
}

TEST(BlockReader, ReusedBlockIsCompletelyOverwritten) {
  TextBlockReader r("/N5 G1 X1 (a) (b) *12\nO7\nG0\n", "p.nc");
  const Block& b = r.block;
  ASSERT_TRUE(r.next());
  EXPECT_TRUE(b.block_delete && b.n && b.checksum && b.comments.size() == 2);
  ASSERT_TRUE(r.next());
  EXPECT_TRUE(b.program_number);
  EXPECT_FALSE(b.block_delete || b.n || b.checksum || !b.comments.empty() || !b.words.empty());
  ASSERT_TRUE(r.next());
  EXPECT_FALSE(b.program_number);
  EXPECT_EQ(b.words.size(), 1U);
  EXPECT_EQ(b.line, 3U);
  EXPECT_FALSE(r.next());
}

TEST(BlockReader, ErrorNamesTheLineOfTheFile) {
  TextBlockReader r("G0 X0\nG1 X1\r\nG1 Y#\r\n", "prog.nc");
  ASSERT_TRUE(r.next());
  ASSERT_TRUE(r.next());
  try {
    r.next();
    FAIL() << "accepted a parameter";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, 3U);
    EXPECT_EQ(e.where().column, 5U);
    EXPECT_EQ(e.where().source_line, "G1 Y#");
    EXPECT_EQ(std::string(e.what()).rfind("prog.nc:3:5: error: bad parameter in word 'Y'", 0), 0U);
  }
}

}  // namespace
