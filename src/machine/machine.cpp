#include "abbe/machine/machine.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <string>
#include <vector>

#include "abbe/io/input_error.hpp"

namespace abbe::machine {

const char* to_string(OutOfRangePolicy p) {
  switch (p) {
    case OutOfRangePolicy::clamp:
      return "clamp";
    case OutOfRangePolicy::extrapolate:
      return "extrapolate";
    case OutOfRangePolicy::error:
      return "error";
  }
  return "?";
}

Machine::Machine(MachineSpec spec) : spec_(std::move(spec)) {
  std::vector<std::string> missing;
  for (Axis a : kAxes) {
    if (spec_.table.axis_has_components(a) && !record(a).present)
      throw InputError({spec_.file, 0, 0, fmt::format("axes.{}", axis_letter(a)), ""},
                       fmt::format("the component table has errors of axis {} but the machine "
                                   "file has no measurement record (measured_at, points) for it",
                                   axis_letter(a)));
    for (int d = 0; d < kComponentsPerAxis; ++d)
      if (!spec_.table.has(ComponentId{a, d})) missing.push_back(component_name({a, d}));
  }
  if (missing.size() == 3 * kComponentsPerAxis)
    spdlog::info("machine \"{}\": the component table is empty (every error taken as zero)",
                 spec_.name);
  else if (!missing.empty())
    spdlog::info("machine \"{}\": no table data for {} (taken as zero)", spec_.name,
                 fmt::join(missing, ", "));
}

Machine Machine::with_campaign(ComponentTable table, std::array<AxisRecord, 3> axes,
                               Squareness squareness) const {
  MachineSpec spec = spec_;
  spec.table = std::move(table);
  spec.axes = axes;
  spec.squareness = squareness;
  return Machine(std::move(spec), Unchecked{});
}

}  // namespace abbe::machine
