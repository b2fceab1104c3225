#include "input_stream.hpp"

#include <cerrno>
#include <cstring>
#include <iostream>

#include "abbe/io/input_error.hpp"

namespace abbe::cli {

InputStream::InputStream(const std::string& path, const char* what) : in_(&std::cin) {
  if (path == "-") return;
  file_.open(path, std::ios::binary);
  if (!file_)
    throw InputError({path, 0, 0, "", ""},
                     std::string("cannot open ") + what + ": " + std::strerror(errno));
  in_ = &file_;
}

long long InputStream::position() {
  if (from_stdin()) return -1;
  return static_cast<long long>(file_.tellg());
}

}  // namespace abbe::cli
