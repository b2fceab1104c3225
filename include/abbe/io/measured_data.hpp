#pragma once
// Measured data (DESIGN.md §4, docs/formats.md): one row per measured point,
// columns in any order, header required; only x, y, z and at least one
// deviation column (dx, dy, dz or dn) are required, empty cells are allowed.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <istream>
#include <limits>
#include <string>
#include <vector>

namespace abbe::io {

struct MeasuredRow {
  static constexpr double kMissing = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();            // nominal tool tip P, mm
  std::array<double, 3> d{kMissing, kMissing, kMissing};  // dx, dy, dz, µm (NaN: absent)
  double t = 0.0;                                         // s
  std::array<std::int8_t, 3> v{0, 0, 0};                  // sign of the last motion per axis
  Eigen::Vector3d n = Eigen::Vector3d::Zero();            // unit surface normal (zero: none)
  double dn = kMissing;                                   // deviation along n, µm
  double tool_length = kMissing;                          // mm (NaN: the machine's default)
  std::string set;                                        // free label
  std::size_t line = 0;                                   // 1-based line in the file

  bool has(int k) const { return d[static_cast<std::size_t>(k)] == d[static_cast<std::size_t>(k)]; }
  bool has_dn() const { return dn == dn; }
  // The row's tool length, or `machine_default` where the file gives none.
  double tool_length_or(double machine_default) const {
    return tool_length == tool_length ? tool_length : machine_default;
  }
};

struct MeasuredData {
  std::string file;
  std::vector<MeasuredRow> rows;
  std::array<bool, 3> has_column{false, false, false};  // dx, dy, dz present in the header
  bool has_dn = false;
};

// Throws abbe::InputError naming the file, line, column and column name.
MeasuredData read_measured_data(std::istream& in, const std::string& file);
// "-" reads standard input.
MeasuredData load_measured_data(const std::string& path);

// Writes rows in the DESIGN.md §4 column order (empty cells for absent values).
std::string measured_data_to_csv(const MeasuredData& data);

}  // namespace abbe::io
