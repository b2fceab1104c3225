#include "abbe/report/svg.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace abbe::report {

std::string escape_xml(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n') break;
        out += c;
    }
  }
  return out;
}

std::string svg_coord(double v) {
  if (!std::isfinite(v)) v = 0.0;
  std::string s = fmt::format("{:.2f}", v);
  // Trim trailing zeros ("12.50" → "12.5", "3.00" → "3").
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (s == "-0" || s.empty()) s = "0";
  return s;
}

void widen_range(double& lo, double& hi) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) {
    lo = 0.0;
    hi = 1.0;
    return;
  }
  if (lo > hi) std::swap(lo, hi);
  if (hi - lo <= 1e-12 * std::max(1.0, std::abs(lo))) {
    const double pad = lo == 0.0 ? 1.0 : 0.1 * std::abs(lo);
    lo -= pad;
    hi += pad;
  }
}

Ticks nice_ticks(double lo, double hi, int target) {
  widen_range(lo, hi);
  target = std::max(target, 2);
  const double raw = (hi - lo) / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / mag;
  // Smallest of 1, 2, 5, 10 (× mag) not below the raw step.
  const double step = mag * (f <= 1.0 ? 1.0 : f <= 2.0 ? 2.0 : f <= 5.0 ? 5.0 : 10.0);
  Ticks t;
  t.step = step;
  const double first = std::ceil(lo / step - 1e-9);
  const double last = std::floor(hi / step + 1e-9);
  for (double k = first; k <= last; k += 1.0) {
    double v = k * step;
    if (std::abs(v) < 1e-12 * step) v = 0.0;
    t.values.push_back(v);
  }
  return t;
}

std::string format_tick(double v, double step) {
  if (!std::isfinite(v)) return "";
  int decimals = 0;
  if (step > 0.0 && std::isfinite(step) && step < 1.0)
    decimals = static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  decimals = std::clamp(decimals, 0, 9);
  std::string s = fmt::format("{:.{}f}", v, decimals);
  if (s.find_first_not_of("-0.") == std::string::npos) s = "0";
  return s;
}

std::string viridis(double t) {
  // Samples of the viridis scale at t = 0, 1/9, …, 1.
  static constexpr std::array<std::array<int, 3>, 10> kStops{{{68, 1, 84},
                                                              {72, 40, 120},
                                                              {62, 73, 137},
                                                              {49, 104, 142},
                                                              {38, 130, 142},
                                                              {31, 158, 137},
                                                              {53, 183, 121},
                                                              {110, 206, 88},
                                                              {181, 222, 43},
                                                              {253, 231, 37}}};
  if (std::isnan(t)) return "#999999";
  t = std::clamp(t, 0.0, 1.0);
  const double x = t * static_cast<double>(kStops.size() - 1);
  const auto i = std::min(static_cast<std::size_t>(x), kStops.size() - 2);
  const double f = x - static_cast<double>(i);
  std::array<int, 3> c{};
  for (std::size_t k = 0; k < 3; ++k)
    c[k] = static_cast<int>(std::lround(kStops[i][k] + f * (kStops[i + 1][k] - kStops[i][k])));
  return fmt::format("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
}

std::string series_colour(std::size_t i) {
  static constexpr std::array<const char*, 8> kColours{"#0072b2", "#e69f00", "#56b4e9", "#cc79a7",
                                                       "#000000", "#d55e00", "#888888", "#f0e442"};
  return kColours[i % kColours.size()];
}

}  // namespace abbe::report
