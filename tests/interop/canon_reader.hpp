#pragma once
// Readers of canonical motion lists for the interop tests: LinuxCNC rs274's
// `-g` output (program units, 4 decimals, mapped to machine-coordinate tool
// tips in mm with the offsets it reports) and `abbe interpret --canon`.
// Shared by canon_compare.cpp and compensated_compare.cpp.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace interop {

enum class Kind { traverse, feed, arc, dwell, other };

inline const char* kind_name(Kind k) {
  switch (k) {
    case Kind::traverse:
      return "STRAIGHT_TRAVERSE";
    case Kind::feed:
      return "STRAIGHT_FEED";
    case Kind::arc:
      return "ARC_FEED";
    case Kind::dwell:
      return "DWELL";
    default:
      return "OTHER";
  }
}

// A motion in machine coordinates (mm), with the slack each number carries.
struct Canon {
  Kind kind = Kind::other;
  std::array<double, 3> end{};
  std::array<double, 3> centre{};  // arcs: full 3-D centre (normal coordinate unused)
  std::array<double, 3> slack{};   // per axis, mm
  int plane = 0;                   // 0 XY, 1 XZ, 2 YZ
  int rotation = 0;
  double feed = 0.0, feed_slack = 0.0;
  double seconds = 0.0;
  double tool_length = 0.0, tool_slack = 0.0;
  std::string text;  // the source line, for messages
};

// Axis index of (first, second, normal) per plane.
constexpr int kAxes[3][3] = {{0, 1, 2}, {2, 0, 1}, {1, 2, 0}};

inline std::vector<double> numbers_in(const std::string& s, std::size_t from) {
  std::vector<double> out;
  const char* p = s.c_str() + from;
  while (*p && *p != ')') {
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p) {
      ++p;
      continue;
    }
    out.push_back(v);
    p = end;
  }
  return out;
}

inline std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

// abbe's message on stderr: the first line with ": error: " (warnings, such
// as the one for rotary words that never move, may come before it), else
// the first line.
inline std::string error_line_of(const std::string& path) {
  std::ifstream in(path);
  std::string line, first;
  bool any = false;
  while (std::getline(in, line)) {
    if (line.find(": error: ") != std::string::npos) return trim(line);
    if (!any) first = line, any = true;
  }
  return trim(first);
}

inline std::vector<Canon> read_rs274(const std::string& path, std::string& error_text) {
  std::ifstream in(path);
  std::vector<Canon> out;
  double u = 1.0;
  std::array<double, 3> g5x{}, g92{}, g5x_slack{}, g92_slack{};
  double feed = 0.0, feed_slack = 0.0, tlo = 0.0, tlo_slack = 0.0;
  int plane = 0;
  std::string line;
  std::vector<std::string> non_canon;  // lines that are not canonical calls: rs274's messages
  while (std::getline(in, line)) {
    // "   12 N..... NAME(args)"
    std::istringstream ls(line);
    std::string seq, n, call;
    ls >> seq >> n;
    const bool canon_line = !seq.empty() && std::isdigit(static_cast<unsigned char>(seq[0])) &&
                            !n.empty() && n[0] == 'N';
    if (!canon_line) {
      if (!trim(line).empty() && trim(line) != "executing") non_canon.push_back(trim(line));
      continue;
    }
    const auto name_at = line.find(n) + n.size();
    call = trim(line.substr(name_at));
    const auto paren = call.find('(');
    if (paren == std::string::npos) continue;
    const std::string name = call.substr(0, paren);
    const std::vector<double> v = numbers_in(call, paren + 1);
    const double res = 0.5e-4 * u;  // half of the last printed digit, mm
    auto printed_slack = [&](double value) { return value != 0.0 ? res : 0.0; };
    // A motion carries the modal feed and tool length offset in force.
    auto push_motion = [&](Canon& c) {
      c.feed = feed;
      c.feed_slack = feed_slack;
      c.tool_length = tlo;
      c.tool_slack = tlo_slack;
      c.text = call;
      out.push_back(c);
    };
    if (name == "USE_LENGTH_UNITS") {
      u = call.find("INCHES") != std::string::npos ? 25.4 : 1.0;
    } else if (name == "SET_G5X_OFFSET" && v.size() >= 4) {
      for (int a = 0; a < 3; ++a) {
        g5x[a] = v[1 + a] * u;
        g5x_slack[a] = printed_slack(v[1 + a]);
      }
    } else if (name == "SET_G92_OFFSET" && v.size() >= 3) {
      for (int a = 0; a < 3; ++a) {
        g92[a] = v[a] * u;
        g92_slack[a] = printed_slack(v[a]);
      }
    } else if (name == "SET_FEED_RATE" && !v.empty()) {
      feed = v[0] * u;
      feed_slack = res;
    } else if (name == "USE_TOOL_LENGTH_OFFSET" && v.size() >= 3) {
      tlo = v[2] * u;
      tlo_slack = printed_slack(v[2]);
    } else if (name == "SELECT_PLANE") {
      plane = call.find("XZ") != std::string::npos   ? 1
              : call.find("YZ") != std::string::npos ? 2
                                                     : 0;
    } else if (name == "STRAIGHT_TRAVERSE" || name == "STRAIGHT_FEED") {
      Canon c;
      c.kind = name == "STRAIGHT_TRAVERSE" ? Kind::traverse : Kind::feed;
      for (int a = 0; a < 3; ++a) {
        c.end[a] = v.at(static_cast<std::size_t>(a)) * u + g5x[a] + g92[a];
        c.slack[a] = res + g5x_slack[a] + g92_slack[a];
      }
      push_motion(c);
    } else if (name == "ARC_FEED" && v.size() >= 6) {
      Canon c;
      c.kind = Kind::arc;
      c.plane = plane;
      const int* ax = kAxes[plane];
      c.end[ax[0]] = v[0] * u;
      c.end[ax[1]] = v[1] * u;
      c.end[ax[2]] = v[5] * u;
      c.centre[ax[0]] = v[2] * u;
      c.centre[ax[1]] = v[3] * u;
      c.rotation = static_cast<int>(std::lround(v[4]));
      for (int a = 0; a < 3; ++a) {
        c.end[a] += g5x[a] + g92[a];
        c.centre[a] += g5x[a] + g92[a];
        c.slack[a] = res + g5x_slack[a] + g92_slack[a];
      }
      push_motion(c);
    } else if (name == "DWELL" && !v.empty()) {
      Canon c;
      c.kind = Kind::dwell;
      c.seconds = v[0];
      c.text = call;
      out.push_back(c);
    } else if (name == "STRAIGHT_PROBE" || name == "RIGID_TAP" || name == "NURBS_FEED" ||
               name == "SPLINE_FEED") {
      Canon c;
      c.kind = Kind::other;
      c.text = call;
      out.push_back(c);
    }
  }
  // rs274 reports its error as a text line (the message), then the block.
  if (non_canon.size() >= 2)
    error_text = non_canon[non_canon.size() - 2];
  else if (!non_canon.empty())
    error_text = non_canon.front();
  return out;
}

inline std::vector<Canon> read_abbe(const std::string& path) {
  std::ifstream in(path);
  std::vector<Canon> out;
  std::string line;
  while (std::getline(in, line)) {
    // "N12 KIND(args) [PLANE=XZ] F=.. TL=.."
    const auto sp = line.find(' ');
    const auto paren = line.find('(');
    if (sp == std::string::npos || paren == std::string::npos) continue;
    const std::string name = line.substr(sp + 1, paren - sp - 1);
    const std::vector<double> v = numbers_in(line, paren + 1);
    Canon c;
    c.text = trim(line);
    auto field = [&](const char* key) {
      const auto at = line.find(key);
      return at == std::string::npos ? 0.0
                                     : std::strtod(line.c_str() + at + std::strlen(key), nullptr);
    };
    c.feed = field(" F=");
    c.tool_length = field(" TL=");
    if (name == "STRAIGHT_TRAVERSE" || name == "STRAIGHT_FEED") {
      c.kind = name == "STRAIGHT_TRAVERSE" ? Kind::traverse : Kind::feed;
      for (int a = 0; a < 3; ++a) c.end[a] = v.at(static_cast<std::size_t>(a));
    } else if (name == "ARC_FEED") {
      c.kind = Kind::arc;
      c.plane = line.find("PLANE=XZ") != std::string::npos   ? 1
                : line.find("PLANE=YZ") != std::string::npos ? 2
                                                             : 0;
      const int* ax = kAxes[c.plane];
      c.end[ax[0]] = v.at(0);
      c.end[ax[1]] = v.at(1);
      c.centre[ax[0]] = v.at(2);
      c.centre[ax[1]] = v.at(3);
      c.rotation = static_cast<int>(std::lround(v.at(4)));
      c.end[ax[2]] = v.at(5);
    } else if (name == "DWELL") {
      c.kind = Kind::dwell;
      c.seconds = v.at(0);
    } else {
      continue;
    }
    out.push_back(c);
  }
  return out;
}

}  // namespace interop
