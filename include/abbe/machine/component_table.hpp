#pragma once
// ComponentTable: the measured component errors of a machine, read from the
// long-form CSV `axis,component,position_mm,direction,value` (docs/formats.md).
// One series per (axis, component, direction); positions strictly increasing.
#include <array>
#include <cstddef>
#include <istream>
#include <string>
#include <vector>

#include "abbe/machine/axis.hpp"

namespace abbe::machine {

enum class TableDirection : std::uint8_t { fwd = 0, rev = 1, mean = 2 };
const char* to_string(TableDirection d);

struct ComponentSeries {
  ComponentId id;
  TableDirection direction = TableDirection::mean;
  std::vector<double> position_mm;  // axis position s_j, strictly increasing
  std::vector<double> value;        // µm (linear) or µrad (angular)
  std::vector<std::size_t> line;    // CSV line of each row (for messages)
  // Standard uncertainty of each value (the table's optional `uncertainty`
  // column, same unit as value); empty when the table has no such column.
  std::vector<double> u;
};

// Unit plausibility limits (docs/formats.md "Unit check"): a linear series
// whose largest |value| is above 0 but below kMinLinearMaxUm over more than
// kUnitCheckSpanMm of travel looks like mm, and an angular value above
// kMaxAngularUrad looks like a wrong unit.
inline constexpr double kMinLinearMaxUm = 0.05;
inline constexpr double kUnitCheckSpanMm = 100.0;
inline constexpr double kMaxAngularUrad = 10000.0;

class ComponentTable {
 public:
  ComponentTable() = default;

  // Parses and validates the CSV text; throws abbe::InputError naming the
  // file, line and column of the first problem.
  static ComponentTable parse(const std::string& text, const std::string& file);
  static ComponentTable load(const std::string& path);

  const std::string& file() const { return file_; }
  const std::vector<ComponentSeries>& series() const { return series_; }
  // nullptr when the table has no such series.
  const ComponentSeries* find(ComponentId id, TableDirection d) const;
  // True when the component has any series (mean, or fwd and rev).
  bool has(ComponentId id) const;
  bool bidirectional(ComponentId id) const;
  bool axis_has_components(Axis a) const;
  // True when the table has the `uncertainty` column.
  bool has_uncertainty() const { return has_uncertainty_; }

  // The same table with other values: `values[i]` replaces series()[i].value
  // (same sizes; a Monte Carlo draw of the campaign). Throws
  // std::invalid_argument when the sizes differ.
  ComponentTable with_values(const std::vector<std::vector<double>>& values) const;

 private:
  static std::size_t slot(ComponentId id, TableDirection d) {
    return static_cast<std::size_t>((index(id.axis) * kComponentsPerAxis + id.d) * 3 +
                                    static_cast<int>(d));
  }
  std::string file_;
  std::vector<ComponentSeries> series_;
  bool has_uncertainty_ = false;
  std::array<int, 3 * kComponentsPerAxis * 3> slot_{};  // index into series_ + 1, 0 = none
};

}  // namespace abbe::machine
