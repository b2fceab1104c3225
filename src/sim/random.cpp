#include "abbe/sim/random.hpp"

#include <cmath>

#include "abbe/io/units.hpp"

namespace abbe::sim {

double Random::uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

double Random::normal() {
  const double u1 = 1.0 - uniform();  // (0, 1]: log is finite
  const double u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(units::kTwoPi * u2);
}

}  // namespace abbe::sim
