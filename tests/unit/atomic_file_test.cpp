// AtomicOutputFile: complete output or none, no temporary files left behind.
#include "abbe/io/atomic_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "abbe/io/input_error.hpp"

namespace abbe::io {
namespace {

namespace fs = std::filesystem;

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("abbe_atomic_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::size_t entries() const {
    return static_cast<std::size_t>(
        std::distance(fs::directory_iterator(dir_), fs::directory_iterator{}));
  }

  fs::path dir_;
};

TEST_F(AtomicFileTest, CommitRenamesTheCompleteFile) {
  const fs::path out = dir_ / "out.csv";
  {
    AtomicOutputFile f(out.string());
    EXPECT_FALSE(f.temp_path().empty());
    EXPECT_EQ(fs::path(f.temp_path()).parent_path(), dir_);
    f.write("hello,", 6);
    f.write("world\n", 6);
    EXPECT_FALSE(fs::exists(out));  // not visible before commit
    f.commit();
  }
  EXPECT_EQ(read(out), "hello,world\n");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(AtomicFileTest, WithoutCommitTheTargetIsUntouched) {
  const fs::path out = dir_ / "out.csv";
  std::ofstream(out) << "old contents\n";
  try {
    AtomicOutputFile f(out.string());
    f.write("partial", 7);
    throw std::runtime_error("bad input half way");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(read(out), "old contents\n");
  EXPECT_EQ(entries(), 1u);  // the temporary file is gone

  {
    AtomicOutputFile f((dir_ / "new.csv").string());
    f.write("x", 1);
  }
  EXPECT_FALSE(fs::exists(dir_ / "new.csv"));
  EXPECT_EQ(entries(), 1u);
}

TEST_F(AtomicFileTest, ReplacesAnExistingFileOnCommit) {
  const fs::path out = dir_ / "out.csv";
  std::ofstream(out) << "old contents\n";
  AtomicOutputFile f(out.string());
  f.write("new\n", 4);
  f.commit();
  EXPECT_EQ(read(out), "new\n");
}

TEST_F(AtomicFileTest, DeviceFilesAreWrittenDirectly) {
  AtomicOutputFile f("/dev/null");
  EXPECT_TRUE(f.temp_path().empty());
  f.write("ignored", 7);
  f.commit();
  EXPECT_TRUE(fs::exists("/dev/null"));
  EXPECT_FALSE(fs::is_regular_file("/dev/null"));
}

TEST_F(AtomicFileTest, MissingDirectoryIsAnInputError) {
  EXPECT_THROW(AtomicOutputFile((dir_ / "no" / "such" / "out.csv").string()), InputError);
  EXPECT_THROW(AtomicOutputFile(dir_.string()), InputError);  // a directory
}

TEST_F(AtomicFileTest, DashIsStandardOutput) {
  AtomicOutputFile f("-");
  EXPECT_TRUE(f.is_stdout());
  EXPECT_EQ(f.stream(), stdout);
  f.commit();
}

}  // namespace
}  // namespace abbe::io
