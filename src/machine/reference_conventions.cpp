#include "abbe/machine/reference_conventions.hpp"

#include <fmt/format.h>

#include "abbe/machine/machine.hpp"

namespace abbe::machine {
namespace {

const char kLetter[3] = {'X', 'Y', 'Z'};

// The squareness of the plane of two directions (u ≠ v).
const char* squareness_of(int u, int v) {
  const int other = 3 - u - v;  // the direction normal to the plane
  return other == 2 ? "EC0Y" : other == 1 ? "EB0Z" : "EA0Z";
}

}  // namespace

bool ReferenceConventions::any() const {
  for (const ComponentConvention& c : component)
    if (c.given) return true;
  return false;
}

ConventionAnalysis analyse_conventions(const Machine& machine) {
  ConventionAnalysis a;
  const ReferenceConventions& rc = machine.spec().conventions;
  const bool same = rc.squareness_same_reference;
  auto shear = [&](const std::string& name, int u, int v, const std::string& what) {
    const char* sq = squareness_of(u, v);
    if (same)
      return fmt::format(
          "{}: {}, a shear in the {}{} plane: absorbed by {} (measured against the "
          "same reference) and a rotation of the set-up",
          name, what, kLetter[std::min(u, v)], kLetter[std::max(u, v)], sq);
    a.aligned_determined = false;
    return fmt::format(
        "{}: {}, a shear in the {}{} plane: NOT absorbed — {} was measured "
        "independently (`conventions.squareness: independent`)",
        name, what, kLetter[std::min(u, v)], kLetter[std::max(u, v)], sq);
  };
  for (Axis j : kAxes)
    for (int d = 0; d < kComponentsPerAxis; ++d) {
      const ComponentId id{j, d};
      const ComponentConvention& c =
          rc.component[static_cast<std::size_t>(index(j) * kComponentsPerAxis + d)];
      if (!c.given) continue;
      a.any = true;
      const std::string name = component_name(id);
      if (id.linear()) {
        a.notes.push_back(
            fmt::format("{}: zeroed at {} mm: a constant offset, absorbed by the "
                        "set-up",
                        name, c.reference_mm));
        if (c.slope_removed) a.notes.push_back(shear(name, d, index(j), "slope removed"));
        continue;
      }
      if (!c.relative) continue;
      // e = θ × (P − M_j(q)) = θ × Σ_{i ∉ U(j)} s_i·e_i + constant: the
      // axes i ≠ θ's own that do not carry j's frame turn θ into shears;
      // two of them make a rotation, none a constant.
      const int about = d - 3;
      std::vector<int> free;
      for (Axis i : kAxes)
        if (index(i) != about && !machine.chain().moves(j, i)) free.push_back(index(i));
      const std::string what = fmt::format("relative to {} mm", c.reference_mm);
      if (free.empty())
        a.notes.push_back(
            fmt::format("{}: {}: a constant offset, absorbed by the set-up", name, what));
      else if (free.size() == 2)
        a.notes.push_back(
            fmt::format("{}: {}: a rotation of the part about the reflector, "
                        "absorbed by the set-up",
                        name, what));
      else
        a.notes.push_back(shear(name, 3 - about - free[0], free[0], what));
    }
  return a;
}

}  // namespace abbe::machine
