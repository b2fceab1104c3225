#include "abbe/io/measured_data.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <optional>
#include <string_view>

#include "abbe/io/csv_fields.hpp"
#include "abbe/io/input_error.hpp"

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
  std::string line;
  std::size_t line_no = 0;
  auto fail = [&](std::size_t column, std::string_view field, const std::string& msg) {
    throw InputError({file, line_no, column, std::string(field), line}, msg);
  };
  // Header: the first non-empty line.
  bool have_header = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (line_no == 1 && line.size() >= 3 && line.compare(0, 3, "\xEF\xBB\xBF") == 0)
      line.erase(0, 3);
    if (!trim_blanks(line).empty()) {
      have_header = true;
      break;
    }
  }
  if (!have_header) {
    line_no = std::max<std::size_t>(line_no, 1);
    fail(1, "header", "empty measured-data file: a header is required");
  }
  std::array<int, kNames.size()> col;
  col.fill(-1);
  const auto names = split_csv_line(line);
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string_view n = trim_blanks(names[i].text);
    for (std::size_t k = 0; k < kNames.size(); ++k)
      if (n == kNames[k]) {
        if (col[k] >= 0) fail(names[i].column, n, fmt::format("column `{}` appears twice", n));
        col[k] = static_cast<int>(i);
      }
  }
  for (int k : {cx, cy, cz})
    if (col[static_cast<std::size_t>(k)] < 0)
      fail(1, "header",
           fmt::format("the header has no `{}` column (x, y, z are required)",
                       kNames[static_cast<std::size_t>(k)]));
  for (int k = 0; k < 3; ++k) data.has_column[static_cast<std::size_t>(k)] = col[cdx + k] >= 0;
  data.has_dn = col[cdn] >= 0;
  if (!data.has_column[0] && !data.has_column[1] && !data.has_column[2] && !data.has_dn)
    fail(1, "header", "the header has no deviation column (dx, dy, dz or dn)");
  if (data.has_dn && (col[cnx] < 0 || col[cny] < 0 || col[cnz] < 0))
    fail(1, "header", "a `dn` column needs the normal columns nx, ny, nz");

  while (std::getline(in, line)) {
    ++line_no;
    if (trim_blanks(line).empty() || trim_blanks(line).front() == '#') continue;
    const auto fields = split_csv_line(line);
    auto text = [&](int k) -> std::optional<CsvField> {  // trimmed
      const int c = col[static_cast<std::size_t>(k)];
      if (c < 0) return std::nullopt;
      const auto uc = static_cast<std::size_t>(c);
      if (uc >= fields.size())
        fail(line.size() + 1, kNames[static_cast<std::size_t>(k)],
             fmt::format("{} fields, but `{}` is column {}", fields.size(),
                         kNames[static_cast<std::size_t>(k)], uc + 1));
      const std::string_view t = trim_blanks(fields[uc].text);
      if (t.empty()) return std::nullopt;
      return CsvField{t, fields[uc].column};
    };
    auto number = [&](int k) -> std::optional<double> {
      auto f = text(k);
      if (!f) return std::nullopt;
      std::string_view t = f->text;
      const char* b = t.data();
      if (*b == '+') ++b;
      double v = 0.0;
      auto [ptr, ec] = std::from_chars(b, t.data() + t.size(), v);
      if (ec != std::errc() || ptr != t.data() + t.size() || !std::isfinite(v))
        fail(f->column, kNames[static_cast<std::size_t>(k)],
             fmt::format("\"{}\" is not a finite number", t));
      return v;
    };
    MeasuredRow r;
    r.line = line_no;
    for (int k = 0; k < 3; ++k) {
      auto v = number(cx + k);
      if (!v) {
        const auto c = static_cast<std::size_t>(col[static_cast<std::size_t>(cx + k)]);
        fail(c < fields.size() ? fields[c].column : 1, kNames[static_cast<std::size_t>(cx + k)],
             "empty coordinate (x, y and z are required on every row)");
      }
      r.p[k] = *v;
      if (auto d = number(cdx + k)) r.d[static_cast<std::size_t>(k)] = *d;
      if (auto s = number(cvx + k)) {
        if (*s != -1.0 && *s != 0.0 && *s != 1.0)
          fail(text(cvx + k)->column, kNames[static_cast<std::size_t>(cvx + k)],
               "the direction of motion must be -1, 0 or 1");
        r.v[static_cast<std::size_t>(k)] = static_cast<std::int8_t>(*s);
      }
      if (auto n = number(cnx + k)) r.n[k] = *n;
    }
    if (auto t = number(ct)) r.t = *t;
    if (auto l = number(cl)) r.tool_length = *l;
    if (auto s = text(cset)) r.set = std::string(s->text);
    if (auto dn = number(cdn)) {
      const double norm = r.n.norm();
      if (std::abs(norm - 1.0) > 1e-3)
        fail(text(cdn)->column, "dn",
             fmt::format("the normal (nx, ny, nz) must be a unit vector (|n| = {:.6g})", norm));
      r.n /= norm;
      r.dn = *dn;
    }
    if (!r.has(0) && !r.has(1) && !r.has(2) && !r.has_dn())
      fail(1, "dx", "the row has no deviation (dx, dy, dz or dn)");
    data.rows.push_back(std::move(r));
  }
  if (data.rows.empty()) throw InputError({file, line_no, 0, "", ""}, "no measured points");
  return data;
}

MeasuredData load_measured_data(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError({path, 0, 0, "", ""},
                     std::string("cannot open the measured data: ") + std::strerror(errno));
  return read_measured_data(in, path);
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
