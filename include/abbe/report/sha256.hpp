#pragma once
// SHA-256 (FIPS 180-4) of the report's inputs, for the footer that says
// exactly which files a report was made from.
#include <string>
#include <string_view>

namespace abbe::report {

// Lower-case hex digest (64 characters).
std::string sha256_hex(std::string_view data);

// Digest of a file's bytes; throws abbe::InputError when it cannot be read.
std::string sha256_file(const std::string& path);

}  // namespace abbe::report
