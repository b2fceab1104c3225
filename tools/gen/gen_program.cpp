// gen_program --blocks N --seed S -o FILE: writes a large, realistic NC
// program for the benchmarks (see program_generator.hpp). The file is written
// atomically; "-" is standard output.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "abbe/io/atomic_file.hpp"
#include "abbe/io/input_error.hpp"
#include "tools/gen/program_generator.hpp"

namespace {
void usage(const char* argv0) {
  std::fprintf(stderr, "usage: %s --blocks N [--seed S] [-o FILE]\n", argv0);
}

bool parse_count(const char* text, unsigned long long& value) {
  char* end = nullptr;
  value = std::strtoull(text, &end, 10);
  return end != text && *end == '\0' && text[0] != '-';
}
}  // namespace

int main(int argc, char** argv) {
  unsigned long long blocks = 0, seed = 1;
  bool have_blocks = false;
  std::string output = "-";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--blocks" && has_value) {
      if (!parse_count(argv[++i], blocks)) return usage(argv[0]), 2;
      have_blocks = true;
    } else if (arg == "--seed" && has_value) {
      if (!parse_count(argv[++i], seed)) return usage(argv[0]), 2;
    } else if ((arg == "-o" || arg == "--output") && has_value) {
      output = argv[++i];
    } else {
      usage(argv[0]);
      return 2;
    }
  }
  if (!have_blocks) return usage(argv[0]), 2;
  try {
    abbe::io::AtomicOutputFile out(output);
    abbe::gen::ProgramGenerator generator(seed);
    fmt::memory_buffer buffer;
    generator.write(static_cast<std::size_t>(blocks), buffer,
                    [&](const fmt::memory_buffer& b) { out.write(b.data(), b.size()); });
    out.commit();
  } catch (const abbe::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
