#pragma once
// One way to open an input file: `path`, or standard input for "-"; a file
// that cannot be opened is bad input naming the file and the reason.
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>

#include "abbe/io/input_error.hpp"

namespace abbe::io {

// Calls read(stream, name) on the opened input; `what` names the file in the
// error ("cannot open the <what>: <reason>").
template <class Read>
auto read_input(const std::string& path, const char* what, Read&& read) {
  if (path == "-") return read(std::cin, std::string("-"));
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError({path, 0, 0, "", ""},
                     std::string("cannot open the ") + what + ": " + std::strerror(errno));
  return read(in, path);
}

}  // namespace abbe::io
