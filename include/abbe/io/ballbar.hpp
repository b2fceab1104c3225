#pragma once
// Importer for circular tests (ISO 230-4, a ballbar or a grid encoder):
// a CSV with one reading per row —
//   plane, radius, cx, cy, cz, feed, direction, angle, dr  [, t] [, set]
// in any order, header names without case (docs/formats.md, "Ballbar
// readings"), read with the one CSV reader (csv_reader.hpp). Becomes
// measured data with the nominal point on the circle, the radial unit
// vector as the normal n and dn = the radial deviation (µm), the signs of
// the last motion of the plane's two axes from the direction of travel,
// and one set per placement (plane and radius) unless a `set` column says
// otherwise.
#include <istream>
#include <string>

#include "abbe/io/measured_data.hpp"

namespace abbe::io {

// Throws abbe::InputError naming the file, line, column and field.
MeasuredData read_ballbar(std::istream& in, const std::string& file);
// "-" reads standard input.
MeasuredData load_ballbar(const std::string& path);

}  // namespace abbe::io
