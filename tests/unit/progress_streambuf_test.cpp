// ProgressStreambuf: a stream read through it gives the same bytes, tellg
// and seekg (verify reads its inputs twice) as the source, and the shared
// counter grows by the bytes read.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "tools/abbe/progress.hpp"

namespace abbe::cli {
namespace {

std::string text_of(std::size_t lines) {
  std::string t;
  for (std::size_t i = 0; i < lines; ++i) t += "G1 X" + std::to_string(i) + " Y-1.5\n";
  return t;
}

TEST(ProgressStreambuf, SameBytesPositionsAndRewind) {
  const std::string text = text_of(20000);  // several 64 KiB buffers
  std::istringstream source(text);
  Progress progress("test", text.size(), false);
  std::uint64_t counter = 0;
  ProgressStreambuf buf(source.rdbuf(), progress, counter);
  std::istream in(&buf);

  std::string line, all;
  std::size_t lines = 0;
  while (std::getline(in, line)) {
    all += line + "\n";
    if (++lines == 7000) {
      EXPECT_EQ(static_cast<std::size_t>(in.tellg()), all.size());
    }
  }
  EXPECT_EQ(all, text);
  EXPECT_EQ(counter, text.size());

  in.clear();
  in.seekg(0);
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line, "G1 X0 Y-1.5");
  EXPECT_EQ(static_cast<std::size_t>(in.tellg()), line.size() + 1);
  std::string rest((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(line + "\n" + rest, text);
  EXPECT_EQ(counter, 2 * text.size());  // read twice
}

TEST(ProgressStreambuf, SharedCounterOverTwoInputs) {
  std::istringstream a("abc\n"), b("defgh\n");
  Progress progress("test", 0, false);
  std::uint64_t counter = 0;
  ProgressStreambuf ba(a.rdbuf(), progress, counter), bb(b.rdbuf(), progress, counter);
  std::istream ia(&ba), ib(&bb);
  std::string s;
  ia >> s;
  ib >> s;
  EXPECT_EQ(s, "defgh");
  EXPECT_EQ(counter, 10u);
}

}  // namespace
}  // namespace abbe::cli
