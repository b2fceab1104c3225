#pragma once
// ErrorComponent: one smooth error motion component of the virtual machine
// (e.g. EXX in µm, EBX in µrad) as a function of the axis position s (mm)
// and the direction of motion:
//   base(s)  = Σ_n poly[n]·uⁿ + Σ_m a_m·sin(2π·s/λ_m + φ_m),  u = (s − centre)/half_range
//   r(s)     = reversal + reversal_slope·u                    (value(↑) − value(↓))
//   value(s, dir) = base(s) + dir·r(s)/2                      (dir ∈ {−1, 0, +1})
// The waves include the ballscrew cycle (λ = screw pitch).
#include <array>
#include <string>
#include <vector>

namespace abbe::sim {

struct Wave {
  double amplitude = 0.0;   // µm or µrad
  double wavelength = 1.0;  // mm
  double phase = 0.0;       // rad
};

struct ErrorComponent {
  double centre = 0.0;      // mm
  double half_range = 1.0;  // mm
  std::vector<double> poly;
  std::vector<Wave> waves;
  double reversal = 0.0;
  double reversal_slope = 0.0;

  double base(double s) const;
  double reversal_at(double s) const;
  double value(double s, int dir) const { return base(s) + 0.5 * dir * reversal_at(s); }
};

// Component index c: 0..2 linear along X, Y, Z (µm), 3..5 angular about X, Y, Z (µrad).
// Name of component c of axis j in ISO 230-1 form: "EXX", "EBX", … ; parse back
// (returns false if `name` is not one).
std::string component_name(int j, int c);
bool parse_component_name(const std::string& name, int& j, int& c);

}  // namespace abbe::sim
