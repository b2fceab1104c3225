#include "abbe/pipeline/point_reader.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <optional>

#include "abbe/io/input_error.hpp"

namespace abbe::pipeline {
namespace {
constexpr std::array<std::string_view, 7> kNames{"x", "y", "z", "vx", "vy", "vz", "tool_length"};
}  // namespace

PointReader::PointReader(std::istream& in, std::string file, double default_tool_length)
    : csv_(in, std::move(file)), default_tool_length_(default_tool_length) {
  csv_.read_header();
  for (std::size_t k = 0; k < kNames.size(); ++k)
    if (const auto c = csv_.column(kNames[k])) col_[k] = static_cast<int>(*c);
  for (std::size_t k = 0; k < 3; ++k)
    if (col_[k] < 0)
      csv_.fail(1, "header",
                fmt::format("the header has no `{}` column (x, y, z are required; found: {})",
                            kNames[k], fmt::join(csv_.header_names(), ", ")));
}

bool PointReader::next(model::EvalPoint& p, std::size_t& line) {
  if (!csv_.next()) return false;
  auto get = [&](std::size_t k) -> std::optional<double> {
    if (col_[k] < 0) return std::nullopt;
    const io::CsvField& f = csv_.field(static_cast<std::size_t>(col_[k]), kNames[k]);
    const auto v = csv_.number(f, kNames[k]);
    if (!v && k < 3) csv_.fail(f.column, kNames[k], "empty coordinate");
    return v;
  };
  for (std::size_t k = 0; k < 3; ++k) p.p[static_cast<Eigen::Index>(k)] = *get(k);
  for (std::size_t k = 0; k < 3; ++k) {
    const auto v = get(3 + k);
    if (v && *v != -1.0 && *v != 0.0 && *v != 1.0)
      csv_.fail(csv_.fields()[static_cast<std::size_t>(col_[3 + k])].column, kNames[3 + k],
                "the direction of motion must be -1, 0 or 1");
    p.dir[k] = static_cast<std::int8_t>(v ? *v : 0.0);
  }
  const auto l = get(6);
  p.tool_length = l ? *l : default_tool_length_;
  p.time = 0.0;
  line = csv_.line();
  return true;
}

}  // namespace abbe::pipeline
