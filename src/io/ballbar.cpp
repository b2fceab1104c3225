#include "abbe/io/ballbar.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <optional>
#include <string_view>

#include "abbe/io/csv_reader.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/io/input_file.hpp"

namespace abbe::io {
namespace {

constexpr std::array<std::string_view, 11> kNames{"plane",     "radius", "cx", "cy", "cz", "feed",
                                                  "direction", "angle",  "dr", "t",  "set"};
enum Col { cplane, cradius, ccx, ccy, ccz, cfeed, cdir, cangle, cdr, ct, cset };
constexpr int kRequired = cdr + 1;

constexpr double kPi = 3.14159265358979323846;

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

int axis_of(char c) {
  switch (c) {
    case 'x':
      return 0;
    case 'y':
      return 1;
    case 'z':
      return 2;
    default:
      return -1;
  }
}

// The circle a reading belongs to: consecutive readings of one circle get
// times from the feed (when the file has no `t`).
struct Circle {
  std::string plane;
  double radius, feed;
  int dir;
  Eigen::Vector3d centre;
  bool operator==(const Circle& o) const {
    return plane == o.plane && radius == o.radius && feed == o.feed && dir == o.dir &&
           centre == o.centre;
  }
};

}  // namespace

MeasuredData read_ballbar(std::istream& in, const std::string& file) {
  MeasuredData data;
  data.file = file;
  data.has_dn = true;
  CsvReader csv(in, file, CsvReader::Options{'#'});
  csv.read_header();
  const auto col = csv.columns(kNames, static_cast<std::size_t>(kRequired),
                               "a ballbar file needs plane, radius, cx, cy, cz, feed, direction, "
                               "angle, dr");

  std::optional<Circle> last;
  double last_angle = 0.0, clock = 0.0;
  while (csv.next()) {
    auto field = [&](int k) {  // trimmed, unquoted; nullopt: no column or empty
      const auto i = static_cast<std::size_t>(k);
      return csv.present_field(col[i], kNames[i]);
    };
    auto required = [&](int k) -> CsvField {
      auto f = field(k);
      if (!f) {
        const auto c = static_cast<std::size_t>(col[static_cast<std::size_t>(k)]);
        csv.fail(c < csv.fields().size() ? csv.fields()[c].column : 1,
                 kNames[static_cast<std::size_t>(k)],
                 fmt::format("empty `{}` (every reading needs it)",
                             kNames[static_cast<std::size_t>(k)]));
      }
      return *f;
    };
    auto number = [&](int k) {
      const CsvField f = required(k);
      return std::make_pair(*csv.number(f, kNames[static_cast<std::size_t>(k)]), f.column);
    };

    const CsvField pf = required(cplane);
    const std::string plane = lower(pf.text);
    const int a = plane.size() == 2 ? axis_of(plane[0]) : -1;
    const int b = plane.size() == 2 ? axis_of(plane[1]) : -1;
    if (a < 0 || b < 0 || a == b)
      csv.fail(pf.column, "plane",
               fmt::format("\"{}\" is not a plane (XY, YZ, ZX, or the same axes the other way "
                           "round: the angle turns from the first axis towards the second)",
                           pf.text));
    const auto [radius, radius_col] = number(cradius);
    if (!(radius > 0.0)) csv.fail(radius_col, "radius", "the radius must be > 0 mm");
    const auto [feed, feed_col] = number(cfeed);
    if (!(feed > 0.0)) csv.fail(feed_col, "feed", "the feed must be > 0 mm/min");
    const CsvField df = required(cdir);
    const std::string d = lower(df.text);
    int dir = 0;
    if (d == "ccw" || d == "+1" || d == "1") dir = 1;
    if (d == "cw" || d == "-1") dir = -1;
    if (dir == 0)
      csv.fail(
          df.column, "direction",
          fmt::format("\"{}\" is not a direction (ccw or +1: the angle grows; cw or -1)", df.text));
    const double angle_deg = number(cangle).first;
    const double dr = number(cdr).first;
    Eigen::Vector3d centre(number(ccx).first, number(ccy).first, number(ccz).first);

    const double ang = angle_deg * kPi / 180.0;
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    n[a] = std::cos(ang);
    n[b] = std::sin(ang);
    MeasuredRow r;
    r.line = csv.line();
    r.p = centre + radius * n;
    r.n = n;
    r.dn = dr;
    // The last motion: along the tangent just before this angle (at a
    // quadrant point the axis that reverses is still moving the old way).
    const double before = ang - dir * 1e-6;
    const double ta = -dir * std::sin(before), tb = dir * std::cos(before);
    r.v[static_cast<std::size_t>(a)] = static_cast<std::int8_t>(ta > 0.0 ? 1 : -1);
    r.v[static_cast<std::size_t>(b)] = static_cast<std::int8_t>(tb > 0.0 ? 1 : -1);
    const Circle circle{plane, radius, feed, dir, centre};
    if (auto f = field(ct)) {
      r.t = *csv.number(*f, "t");
    } else {
      // Time along the file: the arc from the previous reading of the same
      // circle at the feed; nothing is added between circles.
      if (last && *last == circle)
        clock += std::abs(angle_deg - last_angle) * kPi / 180.0 * radius / feed * 60.0;
      r.t = clock;
    }
    last = circle;
    last_angle = angle_deg;
    if (auto s = field(cset)) {
      r.set = std::string(s->text);
    } else {
      std::string p = plane;
      for (char& c : p) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      r.set = fmt::format("{} r{:g}", p, radius);
    }
    data.rows.push_back(std::move(r));
  }
  if (data.rows.empty()) throw InputError({file, csv.line(), 0, "", ""}, "no readings");
  return data;
}

MeasuredData load_ballbar(const std::string& path) {
  return read_input(path, "ballbar file", read_ballbar);
}

}  // namespace abbe::io
