#pragma once
// ReferenceConventions: how the laser software reported each component of
// the table — the optional `conventions` key of the machine file
// (docs/formats.md): zeroed at a reference target, straightness with its
// slope removed, angles relative to the reference position, and whether the
// squareness was measured against the same references. A component without
// an entry is absolute (old files keep their meaning). analyse_conventions
// states, from the chain, which part of the prediction each convention
// leaves free and whether the part's set-up (a translation and a rotation)
// absorbs it (docs/models.md, "Reference conventions and the part").
#include <array>
#include <string>
#include <vector>

#include "abbe/machine/axis.hpp"

namespace abbe::machine {

class Machine;  // machine.hpp

struct ComponentConvention {
  bool given = false;          // an entry in `conventions` (else: absolute)
  double reference_mm = 0.0;   // the reference target / position s_j, mm
  bool slope_removed = false;  // straightness only: about its reference line
  bool relative = false;       // angular only: relative to the reference position
};

struct ReferenceConventions {
  // Per component, index axis·6 + d.
  std::array<ComponentConvention, 3 * kComponentsPerAxis> component{};
  // `squareness: same_reference`: EC0Y, EB0Z, EA0Z were measured against the
  // same reference lines and positions as the tables (else: independently).
  bool squareness_same_reference = false;
  bool any() const;
};

struct ConventionAnalysis {
  bool any = false;                // some component is not absolute
  bool aligned_determined = true;  // the set-up absorbs every free part
  // Per component with a convention: what it leaves free and what absorbs it.
  std::vector<std::string> notes;
};

ConventionAnalysis analyse_conventions(const Machine& machine);

}  // namespace abbe::machine
