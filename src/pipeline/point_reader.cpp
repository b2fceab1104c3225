#include "abbe/pipeline/point_reader.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <optional>

#include "abbe/io/csv_fields.hpp"
#include "abbe/io/input_error.hpp"

namespace abbe::pipeline {
namespace {
constexpr std::array<std::string_view, 7> kNames{"x", "y", "z", "vx", "vy", "vz", "tool_length"};
}  // namespace

PointReader::PointReader(std::istream& in, std::string file, double default_tool_length)
    : in_(in), file_(std::move(file)), default_tool_length_(default_tool_length) {
  if (!next_line())
    throw InputError({file_, 1, 1, "header", ""}, "empty points file: a header is required");
  const auto names = io::split_csv_line(line_);
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string_view n = io::trim_blanks(names[i].text);
    for (std::size_t k = 0; k < kNames.size(); ++k)
      if (n == kNames[k]) {
        if (col_[k] >= 0)
          error(names[i].column, std::string(n), fmt::format("column `{}` appears twice", n));
        col_[k] = static_cast<int>(i);
      }
  }
  for (std::size_t k = 0; k < 3; ++k)
    if (col_[k] < 0)
      error(1, "header",
            fmt::format("the header has no `{}` column (x, y, z are required)", kNames[k]));
}

bool PointReader::next(model::EvalPoint& p, std::size_t& line) {
  while (next_line()) {
    if (io::trim_blanks(line_).empty()) continue;
    const auto fields = io::split_csv_line(line_);
    auto get = [&](std::size_t k) -> std::optional<double> {
      if (col_[k] < 0) return std::nullopt;
      const auto c = static_cast<std::size_t>(col_[k]);
      if (c >= fields.size())
        error(line_.size() + 1, std::string(kNames[k]),
              fmt::format("{} fields, but `{}` is column {}", fields.size(), kNames[k], c + 1));
      const std::string_view t = io::trim_blanks(fields[c].text);
      if (t.empty()) {
        if (k < 3) error(fields[c].column, std::string(kNames[k]), "empty coordinate");
        return std::nullopt;
      }
      double v = 0.0;
      const char* b = t.data();
      if (*b == '+') ++b;
      const auto [ptr, ec] = std::from_chars(b, t.data() + t.size(), v);
      if (ec != std::errc() || ptr != t.data() + t.size() || !std::isfinite(v))
        error(fields[c].column, std::string(kNames[k]),
              fmt::format("\"{}\" is not a finite number", t));
      return v;
    };
    for (std::size_t k = 0; k < 3; ++k) p.p[static_cast<Eigen::Index>(k)] = *get(k);
    for (std::size_t k = 0; k < 3; ++k) {
      const auto v = get(3 + k);
      if (v && *v != -1.0 && *v != 0.0 && *v != 1.0)
        error(fields[static_cast<std::size_t>(col_[3 + k])].column, std::string(kNames[3 + k]),
              "the direction of motion must be -1, 0 or 1");
      p.dir[k] = static_cast<std::int8_t>(v ? *v : 0.0);
    }
    const auto l = get(6);
    p.tool_length = l ? *l : default_tool_length_;
    p.time = 0.0;
    line = line_no_;
    return true;
  }
  return false;
}

bool PointReader::next_line() {
  if (!std::getline(in_, line_)) return false;
  ++line_no_;
  return true;
}

void PointReader::error(std::size_t column, const std::string& field, const std::string& message) {
  throw InputError({file_, line_no_, column, field, line_}, message);
}

}  // namespace abbe::pipeline
