#pragma once
// The input of a command: a file opened in binary mode, or standard input
// when the name is "-". A file that cannot be opened is an abbe::InputError
// naming it ("cannot open <what>: <reason>").
#include <fstream>
#include <istream>
#include <string>

namespace abbe::cli {

class InputStream {
 public:
  InputStream(const std::string& path, const char* what);
  InputStream(const InputStream&) = delete;  // in_ may point at file_
  InputStream& operator=(const InputStream&) = delete;
  std::istream& stream() { return *in_; }
  bool from_stdin() const { return in_ != &file_; }
  // Bytes read so far from a file (-1 for standard input), for progress bars.
  long long position();

 private:
  std::ifstream file_;
  std::istream* in_;
};

}  // namespace abbe::cli
