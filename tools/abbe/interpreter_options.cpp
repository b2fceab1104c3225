#include "interpreter_options.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>

#include "abbe/io/input_error.hpp"

namespace abbe::cli {

[[noreturn]] void bad_option(const std::string& field, const std::string& message) {
  SourceLocation where;
  where.file = "<command line>";
  where.field = field;
  throw InputError(where, message);
}

namespace {

// "n=V": a non-negative tool number and a finite number of mm, for `option`
// (`form` and `example` in the message, `what` names the value).
std::pair<int, double> parse_numbered_mm(const std::string& text, const std::string& option,
                                         const char* form, const char* example, const char* what) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    bad_option(option,
               std::string("expected ") + form + " (e.g. " + example + "), got '" + text + "'");
  int n = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + eq, n);
  if (ec != std::errc() || ptr != text.data() + eq || n < 0)
    bad_option(option, "tool number must be a non-negative integer in '" + text + "'");
  const std::string value = text.substr(eq + 1);
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || end != value.c_str() + value.size() || errno != 0 || !std::isfinite(v))
    bad_option(option, std::string(what) + " must be a number of mm in '" + text + "'");
  return {n, v};
}

}  // namespace

std::pair<int, double> parse_tool_option(const std::string& text) {
  return parse_numbered_mm(text, "--tool", "H=L", "1=200", "tool length");
}

std::pair<int, double> parse_tool_diameter_option(const std::string& text) {
  return parse_numbered_mm(text, "--tool-diameter", "n=D", "1=6", "tool diameter");
}

// "G55=x,y,z": work offset (mm) of G54..G59.
std::pair<std::size_t, Eigen::Vector3d> parse_work_offset_option(const std::string& text) {
  const auto eq = text.find('=');
  const std::string code = text.substr(0, eq);
  static const char* kCodes[6] = {"G54", "G55", "G56", "G57", "G58", "G59"};
  std::size_t index = 6;
  for (std::size_t i = 0; i < 6; ++i)
    if (code == kCodes[i]) index = i;
  if (eq == std::string::npos || index == 6)
    bad_option("--work-offset", "expected G54..G59=x,y,z (mm), got '" + text + "'");
  Eigen::Vector3d v;
  const char* p = text.c_str() + eq + 1;
  for (int a = 0; a < 3; ++a) {
    char* end = nullptr;
    errno = 0;
    v[a] = std::strtod(p, &end);
    if (end == p || errno != 0 || !std::isfinite(v[a]) || (a < 2 && *end != ',') ||
        (a == 2 && *end != '\0'))
      bad_option("--work-offset", "expected G54..G59=x,y,z (mm), got '" + text + "'");
    p = end + 1;
  }
  return {index, v};
}

}  // namespace abbe::cli
