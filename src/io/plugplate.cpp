#include "abbe/io/plugplate.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <vector>

#include "abbe/io/input_error.hpp"
#include "abbe/io/input_file.hpp"

namespace abbe::io {

MeasuredData read_plugplate(std::istream& in, const std::string& file) {
  MeasuredData data;
  data.file = file;
  data.has_column = {true, true, false};
  std::string plate;
  std::string line;
  std::size_t line_no = 0;
  bool header_seen = false;
  auto fail = [&](std::size_t col, const std::string& field, const std::string& msg) {
    throw InputError({file, line_no, col, field, line}, msg);
  };
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::string body = line.substr(first);
    if (body.rfind("Plug Plate:", 0) == 0) {
      std::istringstream s(body.substr(11));
      s >> plate;
      if (plate.empty()) fail(first + 12, "Plug Plate", "no plate id after \"Plug Plate:\"");
      continue;
    }
    if (body.rfind("Date:", 0) == 0) continue;
    if (body.rfind("Meas X", 0) == 0) {
      header_seen = true;
      continue;
    }
    if (!header_seen)
      fail(first + 1, "header",
           "expected the column header \"Meas X Meas Y Nom X Nom Y Err X Err Y ...\" before the "
           "data");
    // Whitespace-separated numbers with their columns.
    std::vector<double> v;
    std::vector<std::size_t> cols;
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i >= line.size()) break;
      const std::size_t start = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
      const std::string tok = line.substr(start, i - start);
      char* end = nullptr;
      errno = 0;
      const double x = std::strtod(tok.c_str(), &end);
      static const char* kField[] = {"Meas X", "Meas Y", "Nom X", "Nom Y", "Err X",
                                     "Err Y",  "Meas D", "Nom D", "Round"};
      const std::string field = v.size() < 9 ? kField[v.size()] : "extra";
      if (end != tok.c_str() + tok.size() || errno == ERANGE || !std::isfinite(x))
        fail(start + 1, field, fmt::format("\"{}\" is not a number", tok));
      v.push_back(x);
      cols.push_back(start + 1);
    }
    if (v.size() < 6)
      fail(line.size() + 1, "Err Y",
           fmt::format("{} numbers, at least 6 expected (Meas X, Meas Y, Nom X, Nom Y, Err X, "
                       "Err Y)",
                       v.size()));
    MeasuredRow r;
    r.line = line_no;
    r.p = Eigen::Vector3d(v[2], v[3], 0.0);
    r.d = {1000.0 * v[4], 1000.0 * v[5], MeasuredRow::kMissing};
    // Err is rounded to 1 µm in the report; Meas − Nom must agree with it.
    for (int k = 0; k < 2; ++k) {
      const double diff = v[static_cast<std::size_t>(k)] - v[static_cast<std::size_t>(2 + k)];
      if (std::abs(diff - v[static_cast<std::size_t>(4 + k)]) > 0.0025)
        fail(cols[static_cast<std::size_t>(4 + k)], k ? "Err Y" : "Err X",
             fmt::format("Err {} = {} mm but Meas − Nom = {:.4f} mm", k ? 'Y' : 'X',
                         v[static_cast<std::size_t>(4 + k)], diff));
    }
    r.set = plate;
    data.rows.push_back(r);
  }
  if (!header_seen) throw InputError({file, line_no, 0, "header", ""}, "no column header found");
  if (data.rows.empty()) throw InputError({file, line_no, 0, "", ""}, "no holes in the report");
  if (plate.empty()) {
    for (auto& r : data.rows) r.set = "plate";
  }
  return data;
}

MeasuredData load_plugplate(const std::string& path) {
  return read_input(path, "plug-plate report", read_plugplate);
}

}  // namespace abbe::io
