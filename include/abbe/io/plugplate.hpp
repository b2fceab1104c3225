#pragma once
// Importer for the CMM reports of SDSS plug plates (docs/diagnosis.md):
// "Plug Plate: N" and "Date:" header lines, a column header, then one hole
// per line: Meas X, Meas Y, Nom X, Nom Y, Err X, Err Y (mm), Meas D, Nom D,
// Round. Becomes measured data with x, y = nominal (mm), z = 0,
// dx, dy = Err in µm and set = the plate id.
#include <istream>
#include <string>

#include "abbe/io/measured_data.hpp"

namespace abbe::io {

// Throws abbe::InputError naming the file, line and column.
MeasuredData read_plugplate(std::istream& in, const std::string& file);
// "-" reads standard input.
MeasuredData load_plugplate(const std::string& path);

}  // namespace abbe::io
