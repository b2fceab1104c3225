#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "abbe/io/input_error.hpp"
#include "expression_eval.hpp"

namespace abbe::gcode {

const char* o_keyword_name(OKeyword keyword) {
  switch (keyword) {
    case OKeyword::sub:
      return "sub";
    case OKeyword::endsub:
      return "endsub";
    case OKeyword::call:
      return "call";
    case OKeyword::return_:
      return "return";
    case OKeyword::do_:
      return "do";
    case OKeyword::while_:
      return "while";
    case OKeyword::endwhile:
      return "endwhile";
    case OKeyword::if_:
      return "if";
    case OKeyword::elseif:
      return "elseif";
    case OKeyword::else_:
      return "else";
    case OKeyword::endif:
      return "endif";
    case OKeyword::break_:
      return "break";
    case OKeyword::continue_:
      return "continue";
    case OKeyword::repeat:
      return "repeat";
    case OKeyword::endrepeat:
      return "endrepeat";
    case OKeyword::none:
      break;
  }
  return "";
}

namespace detail {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kToleranceEqual = 0.0001;  // rs274ngc's TOLERANCE_EQUAL
constexpr std::size_t kMaxStack = 256;
}  // namespace

void fail_at(const CodeSite& site, std::uint32_t column, const std::string& message) {
  throw InputError(
      SourceLocation{site.file, site.line, std::size_t{column} + 1, "", std::string(site.text)},
      message);
}

int integer_value(double value, const CodeSite& site, std::uint32_t column, const char* what) {
  const double r = std::round(value);
  if (!std::isfinite(value) || std::abs(value - r) > kToleranceEqual ||
      std::abs(r) > std::numeric_limits<int>::max())
    fail_at(site, column, fmt::format("{} must be an integer (is {})", what, value));
  return static_cast<int>(r);
}

double evaluate(const Block& block, CodeRange code, const ParameterStore& parameters,
                const CodeSite& site) {
  double stack[kMaxStack];
  std::size_t top = 0;  // number of values on the stack
  const auto need = [&](std::size_t n, const ExprCode& c) {
    if (top < n) fail_at(site, c.column, "malformed expression");  // cannot happen for parsed code
  };
  for (std::uint32_t i = code.begin; i < code.end; ++i) {
    const ExprCode& c = block.code[i];
    switch (c.op) {
      case ExprOp::number:
      case ExprOp::named:
      case ExprOp::exists: {
        if (top == kMaxStack) fail_at(site, c.column, "expression is too deeply nested");
        double v = c.value;
        if (c.op != ExprOp::number) {
          const std::string& name = block.names[c.arg];
          const std::optional<double> p = parameters.find(name);
          if (c.op == ExprOp::exists) {
            v = p ? 1.0 : 0.0;
          } else {
            if (!p)
              fail_at(site, c.column, fmt::format("named parameter #<{}> is not defined", name));
            v = *p;
          }
        }
        stack[top++] = v;
        continue;
      }
      case ExprOp::parameter: {
        need(1, c);
        const int n = integer_value(stack[top - 1], site, c.column, "a parameter number");
        if (!ParameterStore::valid(n))
          fail_at(site, c.column,
                  fmt::format("parameter number #{} is out of range (1 to {})", n,
                              ParameterStore::kCount - 1));
        stack[top - 1] = parameters.get(n);
        continue;
      }
      default:
        break;
    }
    if (c.op >= ExprOp::negate && c.op <= ExprOp::tan) {
      need(1, c);
      double& x = stack[top - 1];
      switch (c.op) {
        case ExprOp::negate:
          x = -x;
          break;
        case ExprOp::abs:
          x = std::abs(x);
          break;
        case ExprOp::acos:
          if (x < -1.0 || x > 1.0)
            fail_at(site, c.column, fmt::format("ACOS of {} (must be between -1 and 1)", x));
          x = std::acos(x) * 180.0 / kPi;
          break;
        case ExprOp::asin:
          if (x < -1.0 || x > 1.0)
            fail_at(site, c.column, fmt::format("ASIN of {} (must be between -1 and 1)", x));
          x = std::asin(x) * 180.0 / kPi;
          break;
        case ExprOp::cos:
          x = std::cos(x * kPi / 180.0);
          break;
        case ExprOp::exp:
          x = std::exp(x);
          break;
        case ExprOp::fix:
          x = std::floor(x);
          break;
        case ExprOp::fup:
          x = std::ceil(x);
          break;
        case ExprOp::ln:
          if (x <= 0.0) fail_at(site, c.column, fmt::format("LN of {} (must be positive)", x));
          x = std::log(x);
          break;
        case ExprOp::round:
          // rs274ngc: (int)(x + 0.5) for x >= 0, (int)(x - 0.5) otherwise
          x = std::trunc(x + (x < 0.0 ? -0.5 : 0.5));
          break;
        case ExprOp::sin:
          x = std::sin(x * kPi / 180.0);
          break;
        case ExprOp::sqrt:
          if (x < 0.0) fail_at(site, c.column, fmt::format("SQRT of {} (must not be negative)", x));
          x = std::sqrt(x);
          break;
        case ExprOp::tan:
          x = std::tan(x * kPi / 180.0);
          break;
        default:
          break;
      }
    } else {
      need(2, c);
      const double b = stack[--top];
      double& a = stack[top - 1];
      switch (c.op) {
        case ExprOp::atan:
          a = std::atan2(a, b) * 180.0 / kPi;
          break;
        case ExprOp::power:
          if (a < 0.0 && std::floor(b) != b)
            fail_at(site, c.column,
                    fmt::format("negative number {} raised to the non-integer power {}", a, b));
          a = std::pow(a, b);
          break;
        case ExprOp::times:
          a = a * b;
          break;
        case ExprOp::divide:
          if (b == 0.0) fail_at(site, c.column, "division by zero");
          a = a / b;
          break;
        case ExprOp::modulo:
          // rs274ngc: fmod, made non-negative; MOD 0 gives NaN there, an error here
          if (b == 0.0) fail_at(site, c.column, "MOD by zero");
          a = std::fmod(a, b);
          if (a < 0.0) a += std::abs(b);
          break;
        case ExprOp::plus:
          a = a + b;
          break;
        case ExprOp::minus:
          a = a - b;
          break;
        case ExprOp::eq:
          a = std::abs(a - b) < kToleranceEqual ? 1.0 : 0.0;
          break;
        case ExprOp::ne:
          a = std::abs(a - b) >= kToleranceEqual ? 1.0 : 0.0;
          break;
        case ExprOp::gt:
          a = a > b ? 1.0 : 0.0;
          break;
        case ExprOp::ge:
          a = a >= b ? 1.0 : 0.0;
          break;
        case ExprOp::lt:
          a = a < b ? 1.0 : 0.0;
          break;
        case ExprOp::le:
          a = a <= b ? 1.0 : 0.0;
          break;
        case ExprOp::and_:
          a = (a == 0.0 || b == 0.0) ? 0.0 : 1.0;
          break;
        case ExprOp::or_:
          a = (a != 0.0 || b != 0.0) ? 1.0 : 0.0;
          break;
        case ExprOp::xor_:
          a = ((a == 0.0) != (b == 0.0)) ? 1.0 : 0.0;
          break;
        default:
          break;
      }
    }
    if (!std::isfinite(stack[top - 1]))
      fail_at(site, c.column, "the expression's value is not a finite number");
  }
  if (top != 1)
    fail_at(site, code.begin < code.end ? block.code[code.begin].column : 0,
            "malformed expression");
  return stack[0];
}

}  // namespace detail
}  // namespace abbe::gcode
