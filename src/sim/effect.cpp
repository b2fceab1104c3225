#include "abbe/sim/effect.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <initializer_list>
#include <stdexcept>
#include <vector>

#include "abbe/io/units.hpp"
#include "abbe/sim/chain_layout.hpp"

namespace abbe::sim {

namespace {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::string cur;
  for (char c : s) {
    if (c == sep) {
      parts.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  parts.push_back(cur);
  return parts;
}

[[noreturn]] void fail(const std::string& text, const std::string& what) {
  throw std::invalid_argument("effect \"" + text + "\": " + what +
                              " (syntax KIND:AXIS:MAGNITUDE[:key=value,...], see "
                              "docs/virtual-machine.md)");
}

double parse_number(const std::string& text, const std::string& s, const std::string& what) {
  if (s.empty()) fail(text, what + " is empty");
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size() || errno != 0 || !std::isfinite(v))
    fail(text, what + " \"" + s + "\" is not a number");
  return v;
}

int parse_axis(const std::string& text, const std::string& s, const std::string& what) {
  if (s.size() != 1 || axis_index(s[0]) < 0) fail(text, what + " \"" + s + "\" is not X, Y or Z");
  return axis_index(s[0]);
}

}  // namespace

const char* to_string(EffectKind kind) {
  switch (kind) {
    case EffectKind::reversal:
      return "reversal";
    case EffectKind::scale:
      return "scale";
    case EffectKind::thermal_drift:
      return "thermal_drift";
    case EffectKind::cyclic:
      return "cyclic";
    case EffectKind::coupling:
      return "coupling";
    case EffectKind::arm_offset:
      return "arm_offset";
    case EffectKind::setup:
      return "setup";
  }
  return "?";
}

Effect parse_effect(const std::string& text) {
  const auto parts = split(text, ':');
  if (parts.size() < 3 || parts.size() > 4) fail(text, "expected 3 or 4 ':'-separated fields");
  Effect e;
  e.text = text;
  const std::string& kind = parts[0];
  const EffectKind kinds[] = {EffectKind::reversal, EffectKind::scale,    EffectKind::thermal_drift,
                              EffectKind::cyclic,   EffectKind::coupling, EffectKind::arm_offset,
                              EffectKind::setup};
  bool found = false;
  for (EffectKind k : kinds)
    if (kind == to_string(k)) {
      e.kind = k;
      found = true;
    }
  if (!found)
    fail(text, "unknown kind \"" + kind +
                   "\" (reversal, scale, thermal_drift, cyclic, coupling, arm_offset, setup)");
  e.axis = parse_axis(text, parts[1], "axis");
  e.direction = e.kind == EffectKind::arm_offset ? 2 : e.axis;

  // Magnitude: number followed by a unit.
  const std::string& mag = parts[2];
  std::size_t k = 0;
  while (k < mag.size() && (std::isdigit(static_cast<unsigned char>(mag[k])) || mag[k] == '.' ||
                            mag[k] == '-' || mag[k] == '+' || mag[k] == 'e' || mag[k] == 'E')) {
    ++k;
  }
  e.magnitude = parse_number(text, mag.substr(0, k), "magnitude");
  e.unit = mag.substr(k);
  if (e.unit == "um/m") e.unit = "ppm";
  if (e.unit == "µm") e.unit = "um";
  if (e.unit == "µrad") e.unit = "urad";
  auto allow = [&](std::initializer_list<const char*> units) {
    for (const char* u : units)
      if (e.unit == u) return;
    std::string list;
    for (const char* u : units) list += std::string(list.empty() ? "" : ", ") + u;
    fail(text, "magnitude needs a unit: one of " + list + " for " + kind);
  };
  switch (e.kind) {
    case EffectKind::reversal:
    case EffectKind::cyclic:
    case EffectKind::coupling:
      allow({"um"});
      break;
    case EffectKind::scale:
      allow({"ppm"});
      break;
    case EffectKind::thermal_drift:
      allow({"um", "ppm"});
      break;
    case EffectKind::arm_offset:
      allow({"mm"});
      break;
    case EffectKind::setup:
      allow({"um", "urad"});
      break;
  }

  if (parts.size() == 4) {
    for (const std::string& kv : split(parts[3], ',')) {
      const auto eq = kv.find('=');
      if (eq == std::string::npos) fail(text, "parameter \"" + kv + "\" is not key=value");
      const std::string key = kv.substr(0, eq), value = kv.substr(eq + 1);
      if (key == "dir") {
        e.direction = parse_axis(text, value, "dir");
      } else if (key == "tau" && e.kind == EffectKind::thermal_drift) {
        e.tau_s = parse_number(text, value, "tau");
        if (e.tau_s <= 0.0) fail(text, "tau must be > 0 s");
      } else if (key == "lag" && e.kind == EffectKind::thermal_drift) {
        e.lag_s = parse_number(text, value, "lag");
        if (e.lag_s < 0.0) fail(text, "lag must be ≥ 0 s");
      } else if (key == "period" && e.kind == EffectKind::cyclic) {
        e.period_mm = parse_number(text, value, "period");
        if (e.period_mm <= 0.0) fail(text, "period must be > 0 mm");
      } else if (key == "phase" && e.kind == EffectKind::cyclic) {
        e.phase_rad = parse_number(text, value, "phase") * units::kPi / 180.0;
      } else if (key == "with" && e.kind == EffectKind::coupling) {
        e.with_axis = parse_axis(text, value, "with");
      } else if (key == "set" && e.kind == EffectKind::setup) {
        e.set = value;
      } else if ((key == "cx" || key == "cy" || key == "cz") && e.kind == EffectKind::setup) {
        e.centre[key[1] - 'x'] = parse_number(text, value, key);
      } else {
        fail(text, "unknown parameter \"" + key + "\" for " + kind);
      }
    }
  }
  if (e.kind == EffectKind::coupling && e.with_axis < 0)
    fail(text, "coupling needs with=AXIS (the second position it depends on)");
  return e;
}

double drift_fraction(double t_s, double tau_s, double lag_s) {
  const double t = std::max(t_s, 0.0);
  if (lag_s <= 0.0) return 1.0 - std::exp(-t / tau_s);
  if (std::abs(tau_s - lag_s) <= 1e-9 * tau_s)
    return 1.0 - (1.0 + t / tau_s) * std::exp(-t / tau_s);
  return 1.0 - (tau_s * std::exp(-t / tau_s) - lag_s * std::exp(-t / lag_s)) / (tau_s - lag_s);
}

}  // namespace abbe::sim
