#include "abbe/compensate/number_format.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace abbe::compensate {

NumberStyle number_style(std::string_view text) {
  NumberStyle s;
  std::size_t i = 0;
  while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) {
    s.plus_sign = text[i] == '+';
    ++i;
  }
  while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
  s.leading_zero = !(i < text.size() && text[i] == '.');
  const std::size_t dot = text.find('.');
  if (dot != std::string_view::npos) {
    int d = 0;
    for (std::size_t k = dot + 1; k < text.size(); ++k)
      if (text[k] >= '0' && text[k] <= '9') ++d;
    s.decimals = d;
  }
  return s;
}

namespace {
double power_of_ten(int decimals) {
  static const double kPow[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  return decimals >= 0 && decimals < 16 ? kPow[decimals] : std::pow(10.0, decimals);
}

}  // namespace

double round_to(double value, int decimals) {
  const double f = power_of_ten(decimals);
  return std::round(value * f) / f;
}

std::string format_number(double value, const NumberStyle& style, int max_decimals) {
  std::string t;
  append_number(t, value, style, max_decimals);
  return t;
}

void append_number(std::string& out, double value, const NumberStyle& style, int max_decimals) {
  const int places = std::max(style.decimals, max_decimals);
  const double scaled = std::round(std::abs(value) * power_of_ten(places));
  if (scaled < 9e15 && places <= 15) {  // the digits of the rounded integer, placed
    auto k = static_cast<unsigned long long>(scaled);
    int shown = places;  // trailing zeros beyond the number's own decimals go
    while (shown > style.decimals && k % 10 == 0) {
      k /= 10;
      --shown;
    }
    char digits[40];
    int n = 0;
    do {
      digits[n++] = static_cast<char>('0' + k % 10);
      k /= 10;
    } while (k > 0 || n <= shown);
    if (scaled > 0.0 && value < 0.0)
      out += '-';  // no negative zero
    else if (style.plus_sign)
      out += '+';
    // digits[shown..n-1]: the integer part, digits[0..shown-1] the decimals.
    const bool bare = !style.leading_zero && shown > 0 && n - 1 == shown && digits[shown] == '0';
    for (int i = n - 1; i >= shown; --i)
      if (!bare) out += digits[i];
    if (shown > 0 || style.point_always) out += '.';
    for (int i = shown - 1; i >= 0; --i) out += digits[i];
    return;
  }
  std::string t = fmt::format("{:.{}f}", round_to(value, places), places);
  if (t.find('.') != std::string::npos) {
    std::size_t keep = t.find('.') + static_cast<std::size_t>(style.decimals);
    while (t.size() - 1 > keep && t.back() == '0') t.pop_back();
    if (t.back() == '.' && style.decimals == 0 && !style.point_always) t.pop_back();
  }
  if (t == "-0" || t.find_first_not_of("-0.") == std::string::npos) {
    if (t[0] == '-') t.erase(0, 1);  // no negative zero
  }
  if (!style.leading_zero) {
    if (t.rfind("0.", 0) == 0)
      t.erase(0, 1);
    else if (t.rfind("-0.", 0) == 0)
      t.erase(1, 1);
  }
  if (style.plus_sign && t[0] != '-') out += '+';
  out += t;  // short: in the string's own buffer, no allocation
}

}  // namespace abbe::compensate
