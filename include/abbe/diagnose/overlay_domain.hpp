#pragma once
// OverlayDomain: where an overlay was fitted — the box of axis positions
// s = P + L·e_z (mm) and the window of campaign time t (s) of the measured
// data `abbe diagnose` found its effects in (docs/formats.md, "Machine
// overlay"). Outside it an overlay's polynomial, smooth and time terms are
// never extrapolated: their arguments are clamped to the domain (the value
// at the nearest point of the box / the nearest end of the window);
// linear geometric terms (scale, squareness) and bounded ones (reversal,
// cyclic) are evaluated as written (EffectDescriptor::extrapolates).
#include <Eigen/Core>
#include <string>

#include "abbe/diagnose/term.hpp"

namespace abbe::diagnose {

struct OverlayDomain {
  bool known = false;                            // false: an overlay written without one
  Eigen::Vector3d lo = Eigen::Vector3d::Zero();  // axis positions s, mm
  Eigen::Vector3d hi = Eigen::Vector3d::Zero();
  double t_lo = 0.0, t_hi = 0.0;  // campaign time, s

  // Inside the box (and, when `with_time`, the time window); true when unknown.
  bool contains(const PointContext& pc, bool with_time) const;
  // pc with s clamped into the box (p moved by the same amount) and t into
  // the window. A point inside is returned unchanged, bit for bit.
  PointContext clamp(const PointContext& pc) const;
  // How far outside: the largest distance beyond the box per axis (mm) and
  // beyond the window (s); zero inside.
  Eigen::Vector3d box_excess(const PointContext& pc) const;
  double time_excess(const PointContext& pc) const;
  // The smallest domain holding both (unknown if either is).
  OverlayDomain merged(const OverlayDomain& other) const;
  // "x −880…−60, y −420…−95, z −350…−120 mm, t 0…7200 s" (time only when asked).
  std::string text(bool with_time) const;
};

// The largest extra deviation an overlay may add at a point, µm: beyond it
// (or a non-finite value) the correction is refused (OverlayExtension).
constexpr double kOverlayLimitUm = 1000.0;

}  // namespace abbe::diagnose
