// cli::Progress: silent when stderr is not a terminal (tests, pipes), and
// the text of the bar.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "tools/abbe/progress.hpp"

namespace abbe::cli {
namespace {

TEST(ReportProgress, BarText) {
  Progress p("predict", 2'000'000, false);
  EXPECT_EQ(p.line(500'000), "predict: [#######.......................]  25% 0.5 MB/2.0 MB");
  EXPECT_EQ(p.line(5'000'000), "predict: [##############################] 100% 5.0 MB/2.0 MB");
  Progress n("map", 0, false, "points");
  EXPECT_EQ(n.line(1234), "map: 1234 points");
}

TEST(ReportProgress, InactiveUnlessEnabledAndATerminal) {
  Progress off("x", 10, false);
  EXPECT_FALSE(off.active());
  Progress on("x", 10, true);
  EXPECT_EQ(on.active(), Progress::stderr_is_terminal());
  on.update(5);
  on.finish();
}

TEST(ReportProgress, FileSize) {
  const std::string path = ::testing::TempDir() + "/progress_size.txt";
  {
    std::ofstream f(path);
    f << "12345";
  }
  EXPECT_EQ(Progress::file_size(path), 5u);
  EXPECT_EQ(Progress::file_size("-"), 0u);
  EXPECT_EQ(Progress::file_size(path + ".missing"), 0u);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace abbe::cli
