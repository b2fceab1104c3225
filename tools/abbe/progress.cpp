#include "progress.hpp"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>

namespace abbe::cli {

Progress::Progress(std::string label, std::uint64_t total, bool enabled, std::string unit)
    : label_(std::move(label)),
      total_(total),
      enabled_(enabled && stderr_is_terminal()),
      unit_(std::move(unit)),
      last_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { finish(); }

bool Progress::stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

std::uint64_t Progress::file_size(const std::string& path) {
  if (path.empty() || path == "-") return 0;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return 0;
  return static_cast<std::uint64_t>(st.st_size);
}

std::string Progress::line(std::uint64_t done) const {
  const bool bytes = unit_ == "bytes";
  auto amount = [&](std::uint64_t v) {
    return bytes ? fmt::format("{:.1f} MB", static_cast<double>(v) / 1e6) : fmt::format("{}", v);
  };
  if (total_ == 0) return fmt::format("{}: {}{}", label_, amount(done), bytes ? "" : " " + unit_);
  const double f = std::min(1.0, static_cast<double>(done) / static_cast<double>(total_));
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(f * kWidth);
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.append(static_cast<std::size_t>(kWidth - filled), '.');
  return fmt::format("{}: [{}] {:3.0f}% {}/{}{}", label_, bar, 100.0 * f, amount(done),
                     amount(total_), bytes ? "" : " " + unit_);
}

void Progress::update(std::uint64_t done) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  drawn_ = true;
  // \r and "erase to end of line": the bar overwrites itself.
  std::fprintf(stderr, "\r%s\x1b[K", line(done).c_str());
  std::fflush(stderr);
}

void Progress::finish() {
  if (!enabled_ || !drawn_) return;
  std::fprintf(stderr, "\r\x1b[K");
  std::fflush(stderr);
  drawn_ = false;
}

ProgressStreambuf::ProgressStreambuf(std::streambuf* source, Progress& progress,
                                     std::uint64_t& counter)
    : source_(source), progress_(progress), counter_(counter) {}

ProgressStreambuf::int_type ProgressStreambuf::underflow() {
  if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
  const std::streamsize n = source_->sgetn(buf_.data(), static_cast<std::streamsize>(buf_.size()));
  if (n <= 0) return traits_type::eof();
  setg(buf_.data(), buf_.data(), buf_.data() + n);
  counter_ += static_cast<std::uint64_t>(n);
  progress_.update(counter_);
  return traits_type::to_int_type(*gptr());
}

ProgressStreambuf::pos_type ProgressStreambuf::seekoff(off_type off, std::ios_base::seekdir dir,
                                                       std::ios_base::openmode which) {
  const auto buffered = static_cast<off_type>(egptr() - gptr());
  if (off == 0 && dir == std::ios_base::cur) {  // tellg(): the source is ahead by the buffer
    const pos_type p = source_->pubseekoff(0, std::ios_base::cur, which);
    return p == pos_type(off_type(-1)) ? p : pos_type(off_type(p) - buffered);
  }
  if (dir == std::ios_base::cur) off -= buffered;
  setg(buf_.data(), buf_.data(), buf_.data());
  return source_->pubseekoff(off, dir, which);
}

ProgressStreambuf::pos_type ProgressStreambuf::seekpos(pos_type pos,
                                                       std::ios_base::openmode which) {
  setg(buf_.data(), buf_.data(), buf_.data());
  return source_->pubseekpos(pos, which);
}

}  // namespace abbe::cli
