// The bad-input corpus: every tests/data/bad/<case>.nc must be refused with an
// abbe::InputError whose text contains tests/data/bad/<case>.expected (the
// first line of the message, "<case>.nc:line:col: error: ..."). Very large
// and binary cases are generated here instead of being committed.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "abbe/gcode/program.hpp"
#include "abbe/io/input_error.hpp"

namespace {

namespace fs = std::filesystem;
using abbe::InputError;

const fs::path kBadDir = fs::path(ABBE_TEST_DATA_DIR) / "bad";

std::vector<std::string> corpus_cases() {
  std::vector<std::string> cases;
  for (const auto& entry : fs::directory_iterator(kBadDir))
    if (entry.path().extension() == ".nc") cases.push_back(entry.path().stem().string());
  std::sort(cases.begin(), cases.end());
  return cases;
}

std::string read_expected(const std::string& name) {
  std::ifstream in(kBadDir / (name + ".expected"));
  std::string line;
  std::getline(in, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line;
}

// Runs `program` through parser and interpreter with default settings and
// a sink that discards; returns the text of the InputError, fails the test if
// the program is accepted.
std::string refusal_text(std::istream& program, const std::string& file) {
  try {
    abbe::gcode::run_program(program, file, abbe::gcode::InterpreterConfig{},
                             [](const abbe::gcode::Motion&) {});
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << file << " was accepted";
  return "";
}

std::string refusal_text(const std::string& text, const std::string& file) {
  std::istringstream in(text);
  return refusal_text(in, file);
}

// A file in a fresh temporary directory, removed at the end of the test.
class TempFile {
 public:
  TempFile(const std::string& name, const std::string& content) {
    std::random_device rd;
    dir_ = fs::temp_directory_path() / ("abbe-bad-input-" + std::to_string(rd()));
    fs::create_directories(dir_);
    path_ = dir_ / name;
    std::ofstream(path_, std::ios::binary) << content;
  }
  ~TempFile() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path dir_;
  fs::path path_;
};

std::string refusal_text_of_file(const TempFile& file) {
  std::ifstream in(file.path(), std::ios::binary);
  return refusal_text(in, file.path().filename().string());
}

TEST(BadInputCorpus, EveryCaseHasANonEmptyExpectedMessage) {
  const auto cases = corpus_cases();
  EXPECT_GE(cases.size(), 20U);
  for (const auto& name : cases) {
    EXPECT_TRUE(fs::exists(kBadDir / (name + ".expected"))) << name << ".nc has no .expected";
    EXPECT_FALSE(read_expected(name).empty()) << name << ".expected is empty";
  }
  // And no .expected without its .nc.
  for (const auto& entry : fs::directory_iterator(kBadDir))
    if (entry.path().extension() == ".expected") {
      fs::path nc = entry.path();
      nc.replace_extension(".nc");
      EXPECT_TRUE(fs::exists(nc)) << entry.path().filename() << " has no .nc";
    }
}

class BadInputCase : public ::testing::TestWithParam<std::string> {};

TEST_P(BadInputCase, IsRefusedWithItsMessage) {
  const std::string name = GetParam();
  const std::string expected = read_expected(name);
  ASSERT_FALSE(expected.empty()) << name << ".expected is missing or empty";
  std::ifstream in(kBadDir / (name + ".nc"), std::ios::binary);
  ASSERT_TRUE(in) << name;
  const std::string what = refusal_text(in, name + ".nc");
  EXPECT_NE(what.find(expected), std::string::npos)
      << "expected: " << expected << "\nactual:   " << what;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadInputCase, ::testing::ValuesIn(corpus_cases()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

TEST(BadInputGenerated, TenMegabyteLineOfWords) {
  std::string text = "G21 G90\nG1 F100 ";
  while (text.size() < (10U << 20)) text += "X1.5 Y-2 ";
  text += "\nM30\n";
  const TempFile file("long-line.nc", text);
  const std::string what = refusal_text_of_file(file);
  EXPECT_NE(what.find("long-line.nc:2:"), std::string::npos) << what.substr(0, 200);
  EXPECT_NE(what.find("error: too many words in one block"), std::string::npos)
      << what.substr(0, 200);
  EXPECT_LT(what.size(), 1000U) << "the message must not quote the whole line";
}

TEST(BadInputGenerated, TenMegabyteNumber) {
  const TempFile file("long-number.nc", "G21\nG0 X-" + std::string(10U << 20, '7') + "\n");
  EXPECT_NE(refusal_text_of_file(file).find(
                "long-number.nc:2:5: error: number is too long (more than 64 characters)"),
            std::string::npos);
}

TEST(BadInputGenerated, TenMegabyteCommentIsFineButTheNextLineIsNot) {
  // A long comment is accepted; the error on the following line proves that
  // the comment line was read and passed.
  const TempFile file("long-comment.nc", "G21 (" + std::string(10U << 20, 'c') + ")\nG0 X#\n");
  EXPECT_NE(
      refusal_text_of_file(file).find("long-comment.nc:2:5: error: bad parameter in word 'X'"),
      std::string::npos);
}

TEST(BadInputGenerated, FileWithoutLineEndsIsRefusedAtTheLineBound) {
  // 17 MiB without a line end (what /dev/zero or a binary file looks like):
  // refused at 16 MiB, not buffered without limit.
  const TempFile file("no-line-end.nc", "G21 (" + std::string(17U << 20, 'c'));
  EXPECT_NE(refusal_text_of_file(file).find(
                "no-line-end.nc:1: error: line reaches 16777216 bytes without a line end"),
            std::string::npos);
}

TEST(BadInputGenerated, NulByte) {
  const TempFile file("nul.nc", std::string("G21\nG0 X1\0 Y2\n", 13));
  EXPECT_NE(refusal_text_of_file(file).find("nul.nc:2:6: error: unexpected byte 0x00"),
            std::string::npos);
}

TEST(BadInputGenerated, BinaryGarbageAfterAValidLine) {
  std::mt19937 rng(7);
  std::string garbage = "G21\n";
  garbage += '\x80';
  for (int i = 0; i < 4096; ++i) garbage += static_cast<char>(rng() & 0xff);
  const TempFile file("garbage.nc", garbage);
  EXPECT_NE(refusal_text_of_file(file).find("garbage.nc:2:1: error: unexpected byte 0x80"),
            std::string::npos);
}

TEST(BadInputGenerated, RandomBinaryFilesAreRefusedCleanly) {
  // Whatever the first bad construct is, the answer is an InputError that
  // names the file and a line (anything else escapes and fails the test).
  for (unsigned seed = 1; seed <= 50; ++seed) {
    std::mt19937 rng(seed);
    std::string bytes;
    for (int i = 0; i < 2048; ++i) bytes += static_cast<char>(rng() & 0xff);
    const std::string what = refusal_text(bytes, "random.nc");
    EXPECT_EQ(what.rfind("random.nc:", 0), 0U) << "seed " << seed << ": " << what.substr(0, 200);
  }
}

}  // namespace
