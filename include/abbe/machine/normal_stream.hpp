#pragma once
// NormalStream: the seeded N(0, 1) deviates of the campaign's Monte Carlo
// draws (machine::draw_campaign): std::mt19937_64 (its sequence is fixed by
// the standard) with the transform done here (Box–Muller, two uniforms per
// deviate), so a seed gives the same draws with every standard library.
#include <cmath>
#include <cstdint>
#include <random>

#include "abbe/io/units.hpp"

namespace abbe::machine {

class NormalStream {
 public:
  explicit NormalStream(std::uint64_t seed) : engine_(seed) {}
  double operator()() {
    const double u1 = 1.0 - uniform();  // (0, 1]: the log is finite
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(units::kTwoPi * u2);
  }

 private:
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  std::mt19937_64 engine_;
};

}  // namespace abbe::machine
