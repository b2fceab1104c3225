#pragma once
// Random: the one source of randomness of the virtual machine. It wraps
// std::mt19937_64 (whose output sequence the C++ standard fixes) and does the
// transforms itself, so a seed gives the same machine with every standard
// library (std::*_distribution output is implementation-defined).
#include <cstdint>
#include <random>

namespace abbe::sim {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  // Uniform on [0, 1): the top 53 bits of one 64-bit draw.
  double uniform();
  // Uniform on [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Standard normal by the Box–Muller transform (two draws per value, no caching).
  double normal();
  // +1 or −1 with equal probability.
  double sign() { return uniform() < 0.5 ? -1.0 : 1.0; }
  // A seed for an independent sub-stream (e.g. the noise of one campaign).
  std::uint64_t next_seed() { return engine_(); }

 private:
  std::mt19937_64 engine_;
};

}  // namespace abbe::sim
