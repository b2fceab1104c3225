#pragma once
// SHA-256 (FIPS 180-4) of bytes and of a file's content, as 64 lowercase hex
// digits: the fingerprint of the machine files a compensated program names
// in its provenance block (docs/compensation.md).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace abbe::io {

class Sha256 {
 public:
  Sha256();
  void update(const void* data, std::size_t size);
  std::string hex();  // finishes the hash; the object is spent afterwards

 private:
  void block(const unsigned char* p);
  std::uint32_t h_[8];
  unsigned char buf_[64];
  std::size_t used_ = 0;
  std::uint64_t bytes_ = 0;
};

std::string sha256_hex(std::string_view data);
// Throws abbe::InputError (naming the path) if the file cannot be read.
std::string sha256_file(const std::string& path);

}  // namespace abbe::io
