#include "abbe/sim/text_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "abbe/io/atomic_file.hpp"
#include "abbe/io/input_error.hpp"

namespace abbe::sim {

namespace {
[[noreturn]] void fail(const std::string& path, const std::string& message) {
  SourceLocation where;
  where.file = path;
  throw InputError(where, message);
}
}  // namespace

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_text_file_atomically(const std::string& path, const std::string& content) {
  io::AtomicOutputFile out(path);
  out.write(content.data(), content.size());
  out.commit();
}

}  // namespace abbe::sim
