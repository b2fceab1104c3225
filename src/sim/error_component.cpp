#include "abbe/sim/error_component.hpp"

#include <cmath>

#include "abbe/io/units.hpp"

namespace abbe::sim {

namespace {}

double ErrorComponent::base(double s) const {
  const double u = (s - centre) / half_range;
  double value = 0.0;
  double un = 1.0;
  for (double c : poly) {
    value += c * un;
    un *= u;
  }
  for (const Wave& w : waves)
    value += w.amplitude * std::sin(units::kTwoPi * s / w.wavelength + w.phase);
  return value;
}

double ErrorComponent::reversal_at(double s) const {
  return reversal + reversal_slope * (s - centre) / half_range;
}

std::string component_name(int j, int c) {
  std::string name = "E";
  name += "XYZABC"[c];
  name += "XYZ"[j];
  return name;
}

bool parse_component_name(const std::string& name, int& j, int& c) {
  if (name.size() != 3 || name[0] != 'E') return false;
  const std::string dirs = "XYZABC", axes = "XYZ";
  const auto cpos = dirs.find(name[1]);
  const auto jpos = axes.find(name[2]);
  if (cpos == std::string::npos || jpos == std::string::npos) return false;
  c = static_cast<int>(cpos);
  j = static_cast<int>(jpos);
  return true;
}

}  // namespace abbe::sim
