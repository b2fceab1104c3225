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
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "canon_reader.hpp"

namespace {

using namespace interop;

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
  const std::string ab_error = error_line_of(argv[4]);
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
