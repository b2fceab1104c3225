#pragma once
// Command-line options that configure the interpreter, shared by `abbe path`
// and `abbe interpret`: --tool H=L and --work-offset G55=x,y,z. Bad values
// are InputErrors naming the option (exit 1).
#include <Eigen/Core>
#include <string>
#include <utility>

namespace abbe::cli {

[[noreturn]] void bad_option(const std::string& field, const std::string& message);

// "H=L": tool length L (mm) for G43 Hn.
std::pair<int, double> parse_tool_option(const std::string& text);
// "n=D": cutter diameter (mm) of tool n, for G41/G42 (--tool-diameter).
std::pair<int, double> parse_tool_diameter_option(const std::string& text);

// "G55=x,y,z": work offset (mm) of G54..G59, as index 0..5 and vector.
std::pair<std::size_t, Eigen::Vector3d> parse_work_offset_option(const std::string& text);

}  // namespace abbe::cli
