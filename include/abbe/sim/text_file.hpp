#pragma once
// Small file helpers of the simulator: read a whole file, write one
// atomically (temporary file in the same directory, then rename).
#include <string>

namespace abbe::sim {

// Throws abbe::InputError naming the path.
std::string read_text_file(const std::string& path);
void write_text_file_atomically(const std::string& path, const std::string& content);

}  // namespace abbe::sim
