#include "abbe/io/measured_data.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
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

constexpr std::array<std::string_view, 16> kNames{"x",  "y",  "z",           "dx", "dy", "dz",
                                                  "t",  "vx", "vy",          "vz", "nx", "ny",
                                                  "nz", "dn", "tool_length", "set"};
enum Col { cx, cy, cz, cdx, cdy, cdz, ct, cvx, cvy, cvz, cnx, cny, cnz, cdn, cl, cset };

}  // namespace

MeasuredData read_measured_data(std::istream& in, const std::string& file) {
  MeasuredData data;
  data.file = file;
  CsvReader csv(in, file, CsvReader::Options{'#'});
  csv.read_header();
  const auto col = csv.columns(kNames, 3, "x, y, z are required");  // kNames starts x, y, z
  for (int k = 0; k < 3; ++k) data.has_column[static_cast<std::size_t>(k)] = col[cdx + k] >= 0;
  data.has_dn = col[cdn] >= 0;
  if (!data.has_column[0] && !data.has_column[1] && !data.has_column[2] && !data.has_dn)
    csv.fail(1, "header", "the header has no deviation column (dx, dy, dz or dn)");
  if (data.has_dn && (col[cnx] < 0 || col[cny] < 0 || col[cnz] < 0))
    csv.fail(1, "header", "a `dn` column needs the normal columns nx, ny, nz");

  while (csv.next()) {
    auto text = [&](int k) {  // trimmed, unquoted; nullopt: no column or empty
      const auto i = static_cast<std::size_t>(k);
      return csv.present_field(col[i], kNames[i]);
    };
    auto number = [&](int k) -> std::optional<double> {
      auto f = text(k);
      if (!f) return std::nullopt;
      return csv.number(*f, kNames[static_cast<std::size_t>(k)]);
    };
    MeasuredRow r;
    r.line = csv.line();
    for (int k = 0; k < 3; ++k) {
      auto v = number(cx + k);
      if (!v) {
        const auto c = static_cast<std::size_t>(col[static_cast<std::size_t>(cx + k)]);
        csv.fail(c < csv.fields().size() ? csv.fields()[c].column : 1,
                 kNames[static_cast<std::size_t>(cx + k)],
                 "empty coordinate (x, y and z are required on every row)");
      }
      r.p[k] = *v;
      if (auto d = number(cdx + k)) r.d[static_cast<std::size_t>(k)] = *d;
      if (auto sgn = number(cvx + k)) {
        if (*sgn != -1.0 && *sgn != 0.0 && *sgn != 1.0)
          csv.fail(text(cvx + k)->column, kNames[static_cast<std::size_t>(cvx + k)],
                   "the direction of motion must be -1, 0 or 1");
        r.v[static_cast<std::size_t>(k)] = static_cast<std::int8_t>(*sgn);
      }
      if (auto n = number(cnx + k)) r.n[k] = *n;
    }
    if (auto t = number(ct)) r.t = *t;
    if (auto l = number(cl)) r.tool_length = *l;
    if (auto st = text(cset)) r.set = std::string(st->text);
    if (auto dn = number(cdn)) {
      const double norm = r.n.norm();
      if (std::abs(norm - 1.0) > 1e-3)
        csv.fail(text(cdn)->column, "dn",
                 fmt::format("the normal (nx, ny, nz) must be a unit vector (|n| = {:.6g})", norm));
      r.n /= norm;
      r.dn = *dn;
    }
    if (!r.has(0) && !r.has(1) && !r.has(2) && !r.has_dn())
      csv.fail(1, "dx", "the row has no deviation (dx, dy, dz or dn)");
    data.rows.push_back(std::move(r));
  }
  if (data.rows.empty()) throw InputError({file, csv.line(), 0, "", ""}, "no measured points");
  return data;
}

MeasuredData load_measured_data(const std::string& path) {
  return read_input(path, "measured data", read_measured_data);
}

std::string measured_data_to_csv(const MeasuredData& data) {
  std::string out = "x,y,z,dx,dy,dz,t,vx,vy,vz,nx,ny,nz,dn,tool_length,set\n";
  auto num = [&](double v) {
    if (v == v) out += fmt::format("{:.6f}", v);
  };
  for (const MeasuredRow& r : data.rows) {
    out += fmt::format("{:.6f},{:.6f},{:.6f},", r.p.x(), r.p.y(), r.p.z());
    for (int k = 0; k < 3; ++k) {
      num(r.d[static_cast<std::size_t>(k)]);
      out += ',';
    }
    out += fmt::format("{:.3f},{},{},{},", r.t, r.v[0], r.v[1], r.v[2]);
    if (r.has_dn())
      out += fmt::format("{:.6f},{:.6f},{:.6f},", r.n.x(), r.n.y(), r.n.z());
    else
      out += ",,,";
    num(r.dn);
    out += ',';
    num(r.tool_length);
    out += ',' + r.set + '\n';
  }
  return out;
}

}  // namespace abbe::io
