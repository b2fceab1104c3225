// canon_compare: compares LinuxCNC rs274's canonical output with
// `abbe interpret --canon` for one NC file and classifies the file.
//
// usage: canon_compare RS274_OUT RS274_EXIT ABBE_OUT ABBE_ERR ABBE_EXIT
// prints one line "<class>\t<motions>\t<detail>" and exits 0, or 1 for a
// mismatch (or an abbe failure that is not a clean refusal).
//
// rs274 prints program coordinates in program units with 4 decimals; they
// are mapped to abbe's machine-coordinate tool tip (mm) with the offsets it
// reports: P = c·u + G5x + G92 (u = 25.4 after USE_LENGTH_UNITS(INCHES));
// the tool length offset is not part of rs274's coordinates, nor of P when
// G43 is active. Agreement is to rs274's printed resolution: 0.5e-4 program
// units per printed number (coordinate and each non-zero printed offset),
// plus 1e-9.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

enum class Kind { traverse, feed, arc, dwell, other };

const char* kind_name(Kind k) {
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

std::vector<double> numbers_in(const std::string& s, std::size_t from) {
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

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

std::string first_line_of(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return trim(line);
}

std::vector<Canon> read_rs274(const std::string& path, std::string& error_text) {
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
      c.feed = feed;
      c.feed_slack = feed_slack;
      c.tool_length = tlo;
      c.tool_slack = tlo_slack;
      c.text = call;
      out.push_back(c);
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
      c.feed = feed;
      c.feed_slack = feed_slack;
      c.tool_length = tlo;
      c.tool_slack = tlo_slack;
      c.text = call;
      out.push_back(c);
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

std::vector<Canon> read_abbe(const std::string& path) {
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

// Empty if equal within the slack, else what differs.
std::string difference(const Canon& r, const Canon& a) {
  constexpr double kEps = 1e-9;
  char buf[256];
  if (r.kind != a.kind)
    return std::string("kind ") + kind_name(r.kind) + " vs " + kind_name(a.kind);
  if (r.kind == Kind::dwell) {
    if (std::abs(r.seconds - a.seconds) > 0.5e-4 + kEps) return "dwell time";
    return "";
  }
  for (int i = 0; i < 3; ++i) {
    if (std::abs(r.end[i] - a.end[i]) > r.slack[i] + kEps) {
      std::snprintf(buf, sizeof buf, "end %c: %.6f vs %.6f (|d| %.3g > %.3g)", "XYZ"[i], r.end[i],
                    a.end[i], std::abs(r.end[i] - a.end[i]), r.slack[i]);
      return buf;
    }
  }
  if (r.kind == Kind::arc) {
    if (r.plane != a.plane) return "plane";
    if (r.rotation != a.rotation) return "rotation (turns, direction)";
    for (int k = 0; k < 2; ++k) {
      const int i = kAxes[r.plane][k];
      if (std::abs(r.centre[i] - a.centre[i]) > r.slack[i] + kEps) {
        std::snprintf(buf, sizeof buf, "centre %c: %.6f vs %.6f", "XYZ"[i], r.centre[i],
                      a.centre[i]);
        return buf;
      }
    }
  }
  if (r.kind == Kind::feed || r.kind == Kind::arc) {
    if (std::abs(r.feed - a.feed) > r.feed_slack + kEps) {
      std::snprintf(buf, sizeof buf, "feed %.4f vs %.4f mm/min", r.feed, a.feed);
      return buf;
    }
  }
  if (std::abs(r.tool_length - a.tool_length) > r.tool_slack + kEps) {
    std::snprintf(buf, sizeof buf, "tool length %.4f vs %.4f mm", r.tool_length, a.tool_length);
    return buf;
  }
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6) {
    std::cerr << "usage: canon_compare RS274_OUT RS274_EXIT ABBE_OUT ABBE_ERR ABBE_EXIT\n";
    return 2;
  }
  std::string rs_error;
  const std::vector<Canon> rs = read_rs274(argv[1], rs_error);
  const int rs_exit = std::atoi(argv[2]);
  const std::vector<Canon> ab = read_abbe(argv[3]);
  const std::string ab_error = first_line_of(argv[4]);
  const int ab_exit = std::atoi(argv[5]);
  const bool rs_refused = rs_exit != 0;

  // abbe must either finish (0) or refuse cleanly (1 with "file:line:col: error: ...").
  if (ab_exit != 0 && !(ab_exit == 1 && ab_error.find(": error: ") != std::string::npos)) {
    std::cout << "abbe-failed\t" << ab.size() << "\texit " << ab_exit << ": " << ab_error << "\n";
    return 1;
  }
  // Every motion abbe made must equal rs274's (the whole sequence when both
  // finished, the common prefix when one refused).
  const std::size_t n = std::min(rs.size(), ab.size());
  for (std::size_t i = 0; i < n; ++i) {
    const std::string d = difference(rs[i], ab[i]);
    if (!d.empty()) {
      std::cout << "mismatch\t" << i << "\tmotion " << i + 1 << ": " << d
                << " | rs274: " << rs[i].text << " | abbe: " << ab[i].text << "\n";
      return 1;
    }
  }
  if (ab_exit == 1) {
    // A refusal must not come after more motions than rs274 made.
    if (ab.size() > rs.size() && !rs_refused) {
      std::cout << "mismatch\t" << n << "\tabbe made more motions before refusing\n";
      return 1;
    }
    std::cout << "refused\t" << ab.size() << "\t" << ab_error
              << (rs_refused ? " [rs274 refuses too: " + rs_error + "]" : "") << "\n";
    return 0;
  }
  if (rs_refused) {
    if (ab.size() < rs.size()) {
      std::cout << "mismatch\t" << n << "\tabbe made fewer motions than rs274 before its error\n";
      return 1;
    }
    std::cout << "rs274-refused\t" << ab.size() << "\trs274: " << rs_error << "\n";
    return 0;
  }
  if (rs.size() != ab.size()) {
    std::cout << "mismatch\t" << n << "\tmotion " << n + 1 << ": rs274 made " << rs.size()
              << " motions, abbe " << ab.size()
              << " | next rs274: " << (n < rs.size() ? rs[n].text : "-")
              << " | next abbe: " << (n < ab.size() ? ab[n].text : "-") << "\n";
    return 1;
  }
  std::cout << "matched\t" << ab.size() << "\t\n";
  return 0;
}
