#include "abbe/machine/campaign_uncertainty.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"

namespace abbe::machine {
namespace {

std::size_t slot(ComponentId id) {
  return static_cast<std::size_t>(index(id.axis) * kComponentsPerAxis + id.d);
}

// Positioning: the linear component along the axis' own direction.
bool positioning(ComponentId id) { return id.d == index(id.axis); }

}  // namespace

bool has_campaign_uncertainty(const Machine& machine) {
  return machine.uncertainty().given || machine.table().has_uncertainty();
}

void require_campaign_uncertainty(const Machine& machine, const std::string& option) {
  if (has_campaign_uncertainty(machine)) return;
  SourceLocation where;
  where.file = machine.spec().file;
  where.field = "uncertainty";
  throw InputError(where, option +
                              ": nothing to propagate: the machine file gives no uncertainty of "
                              "its campaign (no `uncertainty` key, and the component table has no "
                              "`uncertainty` column; docs/formats.md)");
}

std::string campaign_uncertainty_text(const Machine& machine) {
  const CampaignUncertainty& u = machine.uncertainty();
  std::vector<std::string> parts;
  if (machine.table().has_uncertainty()) {
    std::size_t values = 0, nonzero = 0;
    for (const ComponentSeries& s : machine.table().series())
      for (double v : s.u) {
        ++values;
        if (v > 0.0) ++nonzero;
      }
    parts.push_back(
        fmt::format("table values (per-target u, {} of {} values non-zero)", nonzero, values));
  }
  if (u.laser_constant_um > 0.0 || u.laser_ppm > 0.0)
    parts.push_back(
        fmt::format("laser {} µm + {} ppm (positioning)", u.laser_constant_um, u.laser_ppm));
  std::vector<std::string> comps;
  for (Axis a : kAxes)
    for (int d = 0; d < kComponentsPerAxis; ++d) {
      const ComponentId id{a, d};
      const double v = u.component[slot(id)];
      if (v > 0.0)
        comps.push_back(
            fmt::format("{} {} {}", component_name(id), v, id.linear() ? "µm" : "µrad"));
    }
  if (!comps.empty()) parts.push_back("components " + fmt::format("{}", fmt::join(comps, ", ")));
  if (u.reflector_mm > 0.0) parts.push_back(fmt::format("reflector points {} mm", u.reflector_mm));
  const char* sq[3] = {"EC0Y", "EB0Z", "EA0Z"};
  std::vector<std::string> sqs;
  for (std::size_t i = 0; i < 3; ++i)
    if (u.squareness_urad[i] > 0.0)
      sqs.push_back(fmt::format("{} {} µrad", sq[i], u.squareness_urad[i]));
  if (!sqs.empty()) parts.push_back("squareness " + fmt::format("{}", fmt::join(sqs, ", ")));
  if (parts.empty()) return has_campaign_uncertainty(machine) ? "every uncertainty zero" : "none";
  return fmt::format("{}", fmt::join(parts, "; "));
}

Machine draw_campaign(const Machine& machine, const std::function<double()>& standard_normal) {
  const CampaignUncertainty& u = machine.uncertainty();
  const ComponentTable& table = machine.table();

  // The laser's scale error: one deviate per component, shared by its fwd and
  // rev series (same laser, same environment).
  std::array<double, 3 * kComponentsPerAxis> scale{};
  for (double& z : scale) z = standard_normal();

  std::vector<std::vector<double>> values;
  values.reserve(table.series().size());
  for (const ComponentSeries& s : table.series()) {
    std::vector<double> v = s.value;
    const bool pos = positioning(s.id);
    const double uc = u.component[slot(s.id)];
    const double laser_c = pos ? u.laser_constant_um : 0.0;
    const double laser_ppm = pos ? u.laser_ppm : 0.0;
    const double z_scale = scale[slot(s.id)];
    for (std::size_t i = 0; i < v.size(); ++i) {
      const double ut = s.u.empty() ? 0.0 : s.u[i];
      const double z = standard_normal();
      const double u_random = std::sqrt(ut * ut + uc * uc + laser_c * laser_c);
      // ppm × mm = 10⁻³ µm.
      const double u_scale = laser_ppm * 1e-3 * (s.position_mm[i] - s.position_mm.front());
      v[i] += u_random * z + u_scale * z_scale;
    }
    values.push_back(std::move(v));
  }

  // Reflector points: one draw per distinct point of an axis (a point given
  // as `all` is one reflector for its three components).
  std::array<AxisRecord, 3> axes = machine.spec().axes;
  for (AxisRecord& rec : axes) {
    const std::array<Eigen::Vector3d, 3> original = rec.point;
    for (std::size_t k = 0; k < 3; ++k) {
      const Eigen::Vector3d d(standard_normal(), standard_normal(), standard_normal());
      bool shared = false;
      for (std::size_t l = 0; l < k; ++l)
        if (original[l] == original[k]) {
          rec.point[k] = rec.point[l];
          shared = true;
          break;
        }
      if (!shared && rec.present) rec.point[k] = original[k] + u.reflector_mm * d;
    }
  }

  Squareness sq = machine.squareness();
  sq.ec0y += u.squareness_urad[0] * standard_normal();
  sq.eb0z += u.squareness_urad[1] * standard_normal();
  sq.ea0z += u.squareness_urad[2] * standard_normal();
  return machine.with_campaign(table.with_values(values), axes, sq);
}

}  // namespace abbe::machine
