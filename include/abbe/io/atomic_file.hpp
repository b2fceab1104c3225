#pragma once
// AtomicOutputFile: an output that appears complete or not at all. A regular
// file OUT is written as OUT.tmp.XXXXXX in the same directory and renamed over
// OUT by commit(); if commit() is never reached (an exception, an error) the
// temporary file is removed and OUT is left untouched. "-" (or an empty path)
// is standard output; an existing non-regular file (/dev/null, a FIFO) is
// written directly, since it cannot be replaced by a rename.
#include <cstdio>
#include <string>
#include <string_view>

namespace abbe::io {

class AtomicOutputFile {
 public:
  // Opens the output. Throws abbe::InputError (naming the path) if the
  // temporary file cannot be created.
  explicit AtomicOutputFile(std::string path);
  ~AtomicOutputFile();  // removes the temporary file unless committed
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  std::FILE* stream() const { return stream_; }
  const std::string& path() const { return path_; }
  const std::string& temp_path() const { return temp_path_; }  // empty if written directly
  bool is_stdout() const { return is_stdout_; }

  // Writes `size` bytes; throws abbe::InputError on a write error (disk full).
  void write(const char* data, std::size_t size);
  // Flushes, closes and renames the temporary file over the target. Throws
  // abbe::InputError on failure (the temporary file is removed then).
  void commit();

 private:
  void discard() noexcept;

  std::string path_;
  std::string temp_path_;
  std::FILE* stream_ = nullptr;
  bool is_stdout_ = false;
  bool committed_ = false;
  int cleanup_slot_ = -1;  // io/temp_cleanup.hpp: removed on SIGINT/SIGTERM
};

// Writes `text` to `path` through an AtomicOutputFile and commits it.
void write_file_atomically(const std::string& path, std::string_view text);

}  // namespace abbe::io
