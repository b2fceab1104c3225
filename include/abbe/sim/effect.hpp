#pragma once
// Effect: an error source that the virtual machine has but its laser tables
// do not (DESIGN.md §5 kinds), injected so a diagnosis can look for it.
//
// Text form (command line `--inject`, YAML `effects:` list):
//   KIND:AXIS:MAGNITUDE[:key=value[,key=value…]]
// e.g. "reversal:Y:4um", "scale:X:20ppm", "thermal_drift:Z:8um:tau=1200",
// "cyclic:X:1.5um:period=16", "coupling:X:5um:with=Y,dir=Z",
// "arm_offset:Y:50mm:dir=Z", "setup:Z:20urad:set=plate2,cx=-500,cy=-250".
// The full table of kinds, units and keys is in docs/virtual-machine.md.
#include <Eigen/Core>
#include <string>

namespace abbe::sim {

enum class EffectKind { reversal, scale, thermal_drift, cyclic, coupling, arm_offset, setup };

const char* to_string(EffectKind kind);

struct Effect {
  EffectKind kind = EffectKind::reversal;
  int axis = 0;             // the axis whose position (or motion) drives the effect
  int direction = 0;        // the deviation direction (or Δ direction for arm_offset)
  double magnitude = 0.0;   // in `unit`
  std::string unit;         // "um", "urad", "ppm" or "mm"
  double tau_s = 1800.0;    // thermal_drift time constant, s
  double lag_s = 0.0;       // thermal_drift: a second lag in series, s (0: a pure exponential)
  double period_mm = 16.0;  // cyclic period, mm
  double phase_rad = 0.0;   // cyclic phase
  int with_axis = -1;       // coupling partner axis
  std::string set;          // setup: the `set` label it applies to (empty: every point)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // setup rotation centre, mm
  std::string text;                                  // the canonical text form
};

// Throws std::invalid_argument with a message naming the bad part.
Effect parse_effect(const std::string& text);

// The fraction of a thermal drift reached at time t ≥ 0 (0 at t = 0, → 1):
// 1 − e^(−t/τ) for lag 0; with a lag L the step response of two first-order
// lags in series, 1 − (τ·e^(−t/τ) − L·e^(−t/L))/(τ − L) (1 − (1 + t/τ)·e^(−t/τ)
// for L = τ): it starts with zero slope (heat reaching the structure through a
// second body), so it is not an exponential of any τ.
double drift_fraction(double t_s, double tau_s, double lag_s);

}  // namespace abbe::sim
