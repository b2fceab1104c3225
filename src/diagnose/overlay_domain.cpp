#include "abbe/diagnose/overlay_domain.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace abbe::diagnose {

bool OverlayDomain::contains(const PointContext& pc, bool with_time) const {
  if (!known) return true;
  for (int k = 0; k < 3; ++k)
    if (!(pc.s[k] >= lo[k] && pc.s[k] <= hi[k])) return false;
  return !with_time || (pc.t >= t_lo && pc.t <= t_hi);
}

PointContext OverlayDomain::clamp(const PointContext& pc) const {
  PointContext out = pc;
  if (!known) return out;
  for (int k = 0; k < 3; ++k) {
    // std::clamp returns the value itself inside: bit for bit unchanged.
    const double s = std::clamp(pc.s[k], lo[k], hi[k]);
    if (s != pc.s[k]) {
      out.p[k] += s - pc.s[k];
      out.s[k] = s;
    }
  }
  out.t = std::clamp(pc.t, t_lo, t_hi);
  return out;
}

Eigen::Vector3d OverlayDomain::box_excess(const PointContext& pc) const {
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  if (!known) return e;
  for (int k = 0; k < 3; ++k) e[k] = std::max({0.0, lo[k] - pc.s[k], pc.s[k] - hi[k]});
  return e;
}

double OverlayDomain::time_excess(const PointContext& pc) const {
  if (!known) return 0.0;
  return std::max({0.0, t_lo - pc.t, pc.t - t_hi});
}

OverlayDomain OverlayDomain::merged(const OverlayDomain& other) const {
  if (!known || !other.known) return OverlayDomain{};
  OverlayDomain d = *this;
  d.lo = lo.cwiseMin(other.lo);
  d.hi = hi.cwiseMax(other.hi);
  d.t_lo = std::min(t_lo, other.t_lo);
  d.t_hi = std::max(t_hi, other.t_hi);
  return d;
}

std::string OverlayDomain::text(bool with_time) const {
  if (!known) return "unknown";
  std::string s = fmt::format("x {:.6g}…{:.6g}, y {:.6g}…{:.6g}, z {:.6g}…{:.6g} mm", lo[0], hi[0],
                              lo[1], hi[1], lo[2], hi[2]);
  if (with_time) s += fmt::format(", t {:.6g}…{:.6g} s", t_lo, t_hi);
  return s;
}

}  // namespace abbe::diagnose
