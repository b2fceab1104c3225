// The chunked BlockReader: lines that straddle the 1 MiB chunks, CRLF split
// between chunks, a line longer than a chunk, read errors, and the same lines
// and endings as reading the text line by line with std::getline.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <sstream>
#include <streambuf>
#include <string>
#include <vector>

#include "abbe/gcode/parser.hpp"
#include "abbe/io/input_error.hpp"
#include "text_block_reader.hpp"

namespace {

using abbe::InputError;
using abbe::gcode::Block;
using abbe::gcode::BlockReader;
using abbe::gcode::testing::TextBlockReader;

constexpr std::size_t kChunk = std::size_t{1} << 20;

struct ReadLine {
  std::string raw;
  std::string ending;
  std::size_t words = 0;
  double first_value = 0.0;
};

std::vector<ReadLine> read_all(std::istream& in) {
  BlockReader reader(in, "r.nc");
  Block block;
  std::vector<ReadLine> lines;
  while (reader.next(block)) {
    EXPECT_EQ(block.line, lines.size() + 1);
    EXPECT_EQ(reader.line_number(), lines.size() + 1);
    lines.push_back({reader.raw_line(), reader.line_ending(), block.words.size(),
                     block.words.empty() ? 0.0 : block.words[0].value});
  }
  return lines;
}

// The reference: std::getline, '\r' before '\n' (or at the very end) removed.
std::vector<ReadLine> getline_lines(const std::string& text) {
  std::istringstream in(text);
  std::vector<ReadLine> lines;
  std::string line;
  while (std::getline(in, line)) {
    std::string ending = in.eof() ? "" : "\n";
    if (!line.empty() && line.back() == '\r') {
      line.pop_back();
      ending = ending.empty() ? "\r" : "\r\n";
    }
    lines.push_back({line, ending, 0, 0.0});
  }
  return lines;
}

void expect_same_lines(const std::string& text) {
  std::istringstream in(text);
  const std::vector<ReadLine> got = read_all(in);
  const std::vector<ReadLine> want = getline_lines(text);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].raw, want[i].raw) << "line " << i + 1;
    ASSERT_EQ(got[i].ending, want[i].ending) << "line " << i + 1;
  }
}

// Text made of blocks "G1 X<n>" with a line ending per line, then one padded
// with a comment so that its terminator starts at byte `at`, then ten more.
std::string text_with_line_end_at(std::size_t at, const std::string& ending) {
  std::string text;
  int n = 0;
  const std::string filler(4000, 'f');  // long comment lines: few lines to parse
  while (text.size() + 4100 < at) text += "G1 X" + std::to_string(n++) + ";" + filler + ending;
  text += "G1 X1 (" + std::string(at - text.size() - 8, 'p') + ")" + ending;
  for (int i = 0; i < 10; ++i) text += "G1 Y" + std::to_string(i) + ending;
  return text;
}

TEST(BlockReaderChunks, LineEndsAroundTheChunkBoundaryGiveTheGetlineLines) {
  // The terminator of one line falls on each byte around the 1 MiB boundary.
  for (std::size_t at = kChunk - 2; at <= kChunk + 1; ++at) {
    SCOPED_TRACE(at);
    expect_same_lines(text_with_line_end_at(at, "\n"));
    expect_same_lines(text_with_line_end_at(at, "\r\n"));  // CR and LF in different chunks
  }
}

TEST(BlockReaderChunks, ALineLongerThanAChunkIsReadWhole) {
  const std::string comment(3 * kChunk + 17, 'c');
  const std::string text = "G0 X1\nG1 X2 (" + comment + ") Y3\r\nG1 X4";
  std::istringstream in(text);
  const std::vector<ReadLine> lines = read_all(in);
  ASSERT_EQ(lines.size(), 3U);
  EXPECT_EQ(lines[1].raw.size(), comment.size() + 11);
  EXPECT_EQ(lines[1].ending, "\r\n");
  EXPECT_EQ(lines[1].words, 3U);
  EXPECT_EQ(lines[2].raw, "G1 X4");
  EXPECT_EQ(lines[2].ending, "");
  EXPECT_EQ(lines[2].first_value, 1.0);
}

TEST(BlockReaderChunks, RandomTextsGiveTheGetlineLines) {
  std::mt19937 random(7);
  const std::string pieces[] = {"G1 X1.5", "\n", "\r\n", "\n\n", "(c)", " ", "", "N10 M3"};
  for (int round = 0; round < 2; ++round) {
    std::string text;
    while (text.size() < kChunk + kChunk / 2) {
      const std::string& piece = pieces[random() % 8];
      // A line number must come first in its block.
      if (piece[0] == 'N' && !text.empty() && text.back() != '\n') continue;
      text += piece;
    }
    expect_same_lines(text);
  }
  expect_same_lines("");
  expect_same_lines("\n");
  expect_same_lines("\n\n");
  expect_same_lines("G0\r");
  expect_same_lines("\r\n\r\n");
}

TEST(BlockReaderChunks, EmptyInputHasNoLines) {
  TextBlockReader r("", "e.nc");
  EXPECT_FALSE(r.next());
  EXPECT_FALSE(r.next());
  EXPECT_EQ(r.reader.line_number(), 0U);
}

// A stream buffer that delivers `text` 4 KiB at a time (like a pipe) and
// then fails, or ends.
class PieceBuffer : public std::streambuf {
 public:
  PieceBuffer(std::string text, bool fail) : text_(std::move(text)), fail_(fail) {}

 protected:
  int_type underflow() override {
    if (at_ >= text_.size()) {
      if (fail_) throw std::runtime_error("device error");
      return traits_type::eof();
    }
    const std::size_t n = std::min<std::size_t>(4096, text_.size() - at_);
    piece_.assign(text_, at_, n);
    at_ += n;
    setg(piece_.data(), piece_.data(), piece_.data() + n);
    return traits_type::to_int_type(piece_[0]);
  }

 private:
  std::string text_;
  bool fail_;
  std::string piece_;
  std::size_t at_ = 0;
};

// A read error is reported at the line after the complete lines of the
// chunks read before it (the chunk whose read failed is lost, as a failing
// read loses what it was reading).
TEST(BlockReaderChunks, ReadErrorNamesTheLineAfterTheLinesRead) {
  std::string text;
  int n_lines = 0;
  while (text.size() < kChunk + kChunk / 2) text += "G1 X" + std::to_string(n_lines++) + "\n";
  PieceBuffer buffer(text, true);
  std::istream in(&buffer);
  BlockReader reader(in, "dev.nc");
  Block block;
  std::size_t n = 0;
  try {
    while (reader.next(block)) {
      ASSERT_EQ(block.words.size(), 2U);
      EXPECT_EQ(block.words[1].value, static_cast<double>(n));
      ++n;
    }
    FAIL() << "a read error was not reported";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "dev.nc");
    EXPECT_EQ(e.where().line, n + 1);
    EXPECT_NE(e.message().find("read error"), std::string::npos) << e.message();
  }
  // Every complete line of the first chunk came through, nothing after it.
  const std::size_t lines_in_first_chunk =
      static_cast<std::size_t>(std::count(text.begin(), text.begin() + kChunk, '\n'));
  EXPECT_EQ(n, lines_in_first_chunk);
  EXPECT_LT(n, static_cast<std::size_t>(n_lines));
}

TEST(BlockReaderChunks, StreamDeliveredInPiecesIsReadWhole) {
  std::string text;
  for (int i = 0; i < 100000; ++i) text += "G1 X" + std::to_string(i) + "\n";
  PieceBuffer buffer(text, false);
  std::istream piped(&buffer);
  std::size_t n = 0;
  BlockReader reader(piped, "pipe.nc");
  Block block;
  while (reader.next(block)) {
    ASSERT_EQ(block.words.size(), 2U);
    EXPECT_EQ(block.words[1].value, static_cast<double>(n));
    ++n;
  }
  EXPECT_EQ(n, 100000U);
}

}  // namespace
