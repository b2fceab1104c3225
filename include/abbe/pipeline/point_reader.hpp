#pragma once
// PointReader: the points of a CSV file (a CMM or laser grid) as evaluation
// points. Header with x, y, z (required) and optional vx, vy, vz (direction
// signs, −1, 0 or 1) and tool_length; other columns (e.g. measured
// deviations) are ignored. Read by io::CsvReader (BOM, `,` `;` or tab,
// quotes, any case of the header names, CRLF); blank lines are skipped. A
// bad field is an abbe::InputError naming the file, line, column and field.
#include <array>
#include <cstddef>
#include <istream>
#include <string>
#include <string_view>

#include "abbe/io/csv_reader.hpp"
#include "abbe/model/error_model.hpp"

namespace abbe::pipeline {

class PointReader {
 public:
  // Reads the header. `default_tool_length`: for rows without tool_length, mm.
  PointReader(std::istream& in, std::string file, double default_tool_length);

  // The next point and its line number; false at the end of the input.
  bool next(model::EvalPoint& point, std::size_t& line);

 private:
  static constexpr std::size_t kColumns = 7;

  io::CsvReader csv_;
  double default_tool_length_;
  std::array<int, kColumns> col_{-1, -1, -1, -1, -1, -1, -1};
};

}  // namespace abbe::pipeline
