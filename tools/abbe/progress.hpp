#pragma once
// Progress: a one-line progress bar on stderr for long jobs. It draws only
// when enabled and stderr is a terminal (so pipes, logs and tests stay
// silent), at most every 100 ms, and clears its line when finished. The
// amount is whatever the job can count: bytes of the input read so far
// (total = file size) or points processed (total = 0: a count, no bar).
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <streambuf>
#include <string>

namespace abbe::cli {

class Progress {
 public:
  // total = 0: unknown size, shows the amount only. `unit` names the amount
  // ("bytes" is shown as MB).
  Progress(std::string label, std::uint64_t total, bool enabled, std::string unit = "bytes");
  ~Progress();  // finish()
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // True when stderr is a terminal (isatty).
  static bool stderr_is_terminal();
  // The size of a regular file in bytes, 0 if unknown ("-", pipes, errors).
  static std::uint64_t file_size(const std::string& path);

  bool active() const { return enabled_; }
  // Sets the amount done; redraws when due. Cheap when inactive.
  void update(std::uint64_t done);
  // Clears the bar's line (idempotent).
  void finish();

  // The text of the bar for an amount (no terminal codes), for tests.
  std::string line(std::uint64_t done) const;

 private:
  std::string label_;
  std::uint64_t total_;
  bool enabled_;
  std::string unit_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_;
};

// ProgressStreambuf: reads through another stream buffer and reports the
// bytes read so far to a Progress, so that a library loop consuming an
// std::istream shows progress without knowing about it. Repositioning
// (verify reads its inputs twice) is passed on; the amount keeps growing
// (bytes read in total). Several buffers may share one counter (several
// inputs, one bar).
class ProgressStreambuf : public std::streambuf {
 public:
  ProgressStreambuf(std::streambuf* source, Progress& progress, std::uint64_t& counter);

 protected:
  int_type underflow() override;
  pos_type seekoff(off_type off, std::ios_base::seekdir dir,
                   std::ios_base::openmode which) override;
  pos_type seekpos(pos_type pos, std::ios_base::openmode which) override;

 private:
  std::streambuf* source_;
  Progress& progress_;
  std::uint64_t& counter_;
  std::array<char, 1 << 16> buf_{};
};

}  // namespace abbe::cli
