// setup_offset and setup_rotation (catalogue id "setup"): one measured set is
// shifted or rotated as a whole (fixture, part placement).
#include <fmt/format.h>

#include <Eigen/Geometry>  // cross()

#include "abbe/io/units.hpp"
#include "builtin_effects.hpp"

namespace abbe::diagnose::effects {
namespace {

void read_set(Term& t, const OverlayFields& in) { t.set = in.text("set"); }
void write_set(const Term& t, std::string& y) { y += fmt::format("    set: \"{}\"\n", t.set); }

}  // namespace

EffectDescriptor setup_offset() {
  EffectDescriptor d = make_descriptor(TermKind::setup_offset, "setup", "setup_offset");
  d.extrapolates = true;  // a constant
  d.reads_axis = false;
  d.axis_is_direction = true;
  d.basis = [](const Term& t, const PointContext& pc, BasisOut out) {
    if (pc.set == t.set) out(t.direction, 0) = 1.0;
  };
  d.label = [](const Term& t) {
    return fmt::format("setup offset {} [{}]", axis_name(t.direction), t.set);
  };
  d.description = [](const Term& t) {
    return fmt::format("set {} is shifted by {:+.2f} µm along {}: fixture / part placement", t.set,
                       coef_or_zero(t, 0), axis_name(t.direction));
  };
  d.params = [](const Term& t) -> NamedValues { return {{"um", coef_or_zero(t, 0)}}; };
  d.read_fields = read_set;
  d.write_fields = write_set;
  return d;
}

EffectDescriptor setup_rotation() {
  EffectDescriptor d = make_descriptor(TermKind::setup_rotation, "setup", "setup_rotation");
  d.extrapolates = true;  // a rigid rotation
  d.reads_direction = false;
  d.basis = [](const Term& t, const PointContext& pc, BasisOut out) {
    // A small rotation (µrad) about the axis through the centre: ω × (P − C), µm.
    if (pc.set == t.set)
      out.col(0) = units::kUmPerUradMm * Eigen::Vector3d::Unit(t.axis).cross(pc.p - t.centre);
  };
  d.label = [](const Term& t) {
    return fmt::format("setup rotation about {} [{}]", axis_name(t.axis), t.set);
  };
  d.description = [](const Term& t) {
    return fmt::format("set {} is rotated by {:+.2f} µrad about {}: fixture / part placement",
                       t.set, coef_or_zero(t, 0), axis_name(t.axis));
  };
  d.params = [](const Term& t) -> NamedValues { return {{"urad", coef_or_zero(t, 0)}}; };
  d.read_fields = [](Term& t, const OverlayFields& in) {
    read_set(t, in);
    t.centre = read_point(in, "centre");
  };
  d.write_fields = [](const Term& t, std::string& y) {
    write_set(t, y);
    y += fmt::format("    centre: {}\n", yaml_list(t.centre.data(), 3));
  };
  return d;
}

}  // namespace abbe::diagnose::effects
