#include "abbe/io/atomic_file.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "abbe/io/input_error.hpp"
#include "abbe/io/temp_cleanup.hpp"

namespace abbe::io {

namespace {
[[noreturn]] void fail(const std::string& path, const std::string& what) {
  SourceLocation where;
  where.file = path;
  throw InputError(where, what + ": " + std::strerror(errno));
}
}  // namespace

AtomicOutputFile::AtomicOutputFile(std::string path) : path_(std::move(path)) {
  if (path_.empty() || path_ == "-") {
    stream_ = stdout;
    is_stdout_ = true;
    return;
  }
  struct stat st {};
  if (::stat(path_.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode)) {
      errno = EISDIR;
      fail(path_, "cannot write output");
    }
    stream_ = std::fopen(path_.c_str(), "wb");
    if (!stream_) fail(path_, "cannot open output");
    return;
  }
  std::vector<char> name(path_.begin(), path_.end());
  const char suffix[] = ".tmp.XXXXXX";
  name.insert(name.end(), suffix, suffix + sizeof(suffix));  // includes the '\0'
  const int fd = ::mkstemp(name.data());
  if (fd < 0) fail(path_, "cannot create a temporary file next to the output");
  temp_path_ = name.data();
  // mkstemp creates the file with mode 0600; give it the usual mode (0666 & ~umask).
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, static_cast<mode_t>(0666 & ~mask));
  stream_ = ::fdopen(fd, "wb");
  if (!stream_) {
    const int saved = errno;
    ::close(fd);
    ::unlink(temp_path_.c_str());
    errno = saved;
    fail(path_, "cannot open the temporary output file");
  }
  cleanup_slot_ = register_temp_file(temp_path_.c_str());
}

AtomicOutputFile::~AtomicOutputFile() {
  if (!committed_) discard();
}

void AtomicOutputFile::discard() noexcept {
  if (stream_ && !is_stdout_) std::fclose(stream_);
  if (is_stdout_ && stream_) std::fflush(stream_);
  stream_ = nullptr;
  if (!temp_path_.empty()) ::unlink(temp_path_.c_str());
  unregister_temp_file(cleanup_slot_);
  cleanup_slot_ = -1;
}

void AtomicOutputFile::write(const char* data, std::size_t size) {
  if (size == 0) return;
  if (std::fwrite(data, 1, size, stream_) != size) fail(path_, "cannot write output");
}

void AtomicOutputFile::commit() {
  if (committed_) return;
  if (std::fflush(stream_) != 0) {
    const int saved = errno;
    discard();
    errno = saved;
    fail(path_, "cannot write output");
  }
  if (is_stdout_) {
    committed_ = true;
    return;
  }
  const int rc = std::fclose(stream_);
  stream_ = nullptr;
  if (rc != 0) {
    const int saved = errno;
    discard();
    errno = saved;
    fail(path_, "cannot write output");
  }
  if (!temp_path_.empty() && std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    const int saved = errno;
    discard();
    errno = saved;
    fail(path_, "cannot rename the temporary file to the output");
  }
  unregister_temp_file(cleanup_slot_);
  cleanup_slot_ = -1;
  committed_ = true;
}

void write_file_atomically(const std::string& path, std::string_view text) {
  AtomicOutputFile f(path);
  f.write(text.data(), text.size());
  f.commit();
}

}  // namespace abbe::io
