#include "abbe/io/laser_export.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <sstream>
#include <tuple>

#include "abbe/io/csv_reader.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/io/input_file.hpp"
#include "abbe/io/units.hpp"

namespace abbe::io {
namespace {

constexpr double kSameTargetMm = 1e-6;  // targets within 1 nm are one target

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

// One `# key: value` line.
struct Meta {
  bool seen = false;
  std::string value;
  std::size_t line = 0, column = 0;
  std::string text;  // the whole line, for the caret display
};

[[noreturn]] void fail_at(const std::string& file, const Meta& m, const std::string& field,
                          const std::string& message) {
  throw InputError({file, m.line, m.column, field, m.text}, message);
}

// The text with every line that starts (after blanks, a BOM) with '#' made
// empty; the line breaks are kept.
std::string blank_comments(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::size_t first = pos;
    if (pos == 0 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) first = 3;
    while (first < end && (text[first] == ' ' || text[first] == '\t')) ++first;
    if (!(first < end && text[first] == '#')) out.append(text, pos, end - pos);
    if (end < text.size()) out += '\n';
    pos = end + 1;
  }
  return out;
}

// The index of a metadata key (axis, component, units, reference,
// environment compensation; lower case, with their other spellings), −1 for
// another key.
int metadata_key(const std::string& key) {
  if (key == "axis") return 0;
  if (key == "component") return 1;
  if (key == "units" || key == "unit") return 2;
  if (key == "reference" || key == "reference target") return 3;
  if (key == "environment compensation" || key == "environment") return 4;
  return -1;
}

// A line `# key: value` with a metadata key.
bool is_metadata_line(const std::string& l) {
  const auto hash = l.find_first_not_of(" \t");
  if (hash == std::string::npos || l[hash] != '#') return false;
  const auto colon = l.find(':', hash);
  return colon != std::string::npos &&
         metadata_key(lower(trim(l.substr(hash + 1, colon - hash - 1)))) >= 0;
}

}  // namespace

std::optional<LaserUnit> parse_laser_unit(const std::string& text) {
  const std::string t = lower(trim(text));
  if (t == "µm" || t == "um" || t == "μm") return LaserUnit::um;  // micro sign or Greek mu
  if (t == "mm") return LaserUnit::mm;
  if (t == "arcsec" || t == "arc-sec" || t == "arc-seconds" || t == "arcseconds" || t == "\"")
    return LaserUnit::arcsec;
  if (t == "µrad" || t == "urad" || t == "μrad") return LaserUnit::urad;
  if (t == "mm/m") return LaserUnit::mm_per_m;
  return std::nullopt;
}

bool is_angular(LaserUnit unit) { return unit != LaserUnit::um && unit != LaserUnit::mm; }

double laser_unit_factor(LaserUnit unit) {
  switch (unit) {
    case LaserUnit::um:
      return 1.0;
    case LaserUnit::mm:
      return units::kUmPerMm;
    case LaserUnit::arcsec:
      return units::kPi / 648000.0 * units::kUradPerRad;  // 1″ = π/648000 rad
    case LaserUnit::urad:
      return 1.0;
    case LaserUnit::mm_per_m:
      return 1e-3 * units::kUradPerRad;  // 1 mm/m = 10⁻³ rad
  }
  return 1.0;
}

LaserExport read_laser_export(std::istream& in, const std::string& file) {
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  LaserExport d;
  d.file = file;

  // The metadata: `# key: value` lines (keys without case; other comment
  // lines and unknown keys — date, operator, … — are skipped).
  Meta axis, component, units, reference, environment;
  {
    std::istringstream lines(text);
    std::string raw;
    std::size_t line_no = 0;
    while (std::getline(lines, raw)) {
      ++line_no;
      std::string l = raw;
      if (line_no == 1 && l.compare(0, 3, "\xEF\xBB\xBF") == 0) l.replace(0, 3, "   ");
      const auto hash = l.find_first_not_of(" \t");
      if (hash == std::string::npos || l[hash] != '#') continue;
      const auto colon = l.find(':', hash);
      if (colon == std::string::npos) continue;
      const std::string key = lower(trim(l.substr(hash + 1, colon - hash - 1)));
      Meta* const metas[] = {&axis, &component, &units, &reference, &environment};
      const int k = metadata_key(key);
      Meta* m = k < 0 ? nullptr : metas[k];
      if (!m) continue;
      Meta here;
      here.seen = true;
      here.line = line_no;
      here.text = raw;
      const auto v = l.find_first_not_of(" \t", colon + 1);
      here.column = (v == std::string::npos ? l.size() : v) + 1;
      here.value = trim(l.substr(colon + 1));
      if (m->seen)
        fail_at(file, here, key,
                fmt::format("`{}` is given twice (first on line {})", key, m->line));
      *m = here;
    }
  }
  auto require = [&](const Meta& m, const char* key) {
    if (!m.seen || m.value.empty())
      throw InputError({file, m.line, m.column, key, m.text},
                       fmt::format("the export needs a metadata line `# {}: …` before the "
                                   "readings (docs/formats.md, \"Laser calibration export\")",
                                   key));
  };
  require(axis, "axis");
  require(component, "component");
  require(units, "units");

  const std::string a = lower(axis.value);
  if (a != "x" && a != "y" && a != "z")
    fail_at(file, axis, "axis", fmt::format("unknown axis \"{}\" (X, Y or Z)", axis.value));
  d.axis = static_cast<char>(std::toupper(static_cast<unsigned char>(a[0])));

  std::string c = component.value;
  for (char& ch : c) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  if (c.size() != 3 || c[0] != 'E' || std::string("XYZABC").find(c[1]) == std::string::npos ||
      std::string("XYZ").find(c[2]) == std::string::npos)
    fail_at(file, component, "component",
            fmt::format("\"{}\" is not an ISO 230-1 component name (EXX, EYX, …, ECZ; squareness "
                        "is not measured along one axis)",
                        component.value));
  if (c[2] != d.axis)
    fail_at(file, component, "component",
            fmt::format("component {} belongs to axis {}, not {}", c, c[2], d.axis));
  d.component = c;
  d.angular = std::string("ABC").find(c[1]) != std::string::npos;

  const auto unit = parse_laser_unit(units.value);
  if (!unit)
    fail_at(file, units, "units",
            fmt::format("unknown unit \"{}\" (µm, um, mm for linear components; arcsec, \", "
                        "µrad, urad, mm/m for angular ones)",
                        units.value));
  if (is_angular(*unit) != d.angular)
    fail_at(file, units, "units",
            fmt::format("{} is {} but the unit {} is {}: refused (a table is converted, never "
                        "reinterpreted)",
                        c, d.angular ? "angular" : "linear", units.value,
                        is_angular(*unit) ? "angular" : "linear"));
  d.unit = *unit;
  d.unit_text = units.value;
  const double factor = laser_unit_factor(*unit);

  if (reference.seen) {
    const auto r = parse_csv_number(reference.value);
    if (!r)
      fail_at(file, reference, "reference",
              fmt::format("\"{}\" is not a target position (mm)", reference.value));
    d.reference_mm = *r;
  }
  if (environment.seen) {
    const std::string e = lower(environment.value);
    if (e == "automatic" || e == "auto" || e == "on" || e == "yes")
      d.environment_compensation = "automatic";
    else if (e == "manual")
      d.environment_compensation = "manual";
    else if (e == "off" || e == "none" || e == "no")
      d.environment_compensation = "off";
    else
      fail_at(file, environment, "environment compensation",
              fmt::format("\"{}\" is not one of automatic, manual, off", environment.value));
  }

  // The readings: one CSV reader for every CSV (BOM, separators, quotes,
  // header names without case, decimal commas with `;`). The metadata lines
  // are handed to it blank (a unit `"` must not open a quoted field), so its
  // line numbers stay those of the file.
  std::istringstream body(blank_comments(text));
  CsvReader csv(body, file, CsvReader::Options{'#'});
  csv.read_header();
  std::size_t col[4];
  const char* names[4] = {"target", "run", "direction", "reading"};
  for (int i = 0; i < 4; ++i) {
    const auto c_i = csv.column(names[i]);
    if (!c_i)
      csv.fail(1, "header",
               fmt::format("no column `{}` (the columns are target, run, direction, reading, in "
                           "any order)",
                           names[i]));
    col[i] = *c_i;
  }
  std::map<std::tuple<long long, int, int>, std::size_t> seen;  // (target in nm, run, dir) -> line
  while (csv.next()) {
    LaserReading r;
    r.line = csv.line();
    const CsvField& ft = csv.field(col[0], "target");
    const auto target = csv.number(ft, "target");
    if (!target) csv.fail(ft.column, "target", "the target is empty");
    r.target_mm = *target;
    const CsvField& fr = csv.field(col[1], "run");
    const auto run = csv.number(fr, "run");
    if (!run || *run < 1.0 || *run > 1e6 || std::floor(*run) != *run)
      csv.fail(fr.column, "run", fmt::format("\"{}\" is not a run number (1, 2, …)", fr.text));
    r.run = static_cast<int>(*run);
    const CsvField& fd = csv.field(col[2], "direction");
    const std::string dir = lower(std::string(fd.text));
    if (dir == "up" || dir == "fwd" || dir == "forward" || dir == "+")
      r.dir = +1;
    else if (dir == "down" || dir == "rev" || dir == "reverse" || dir == "-")
      r.dir = -1;
    else
      csv.fail(fd.column, "direction",
               fmt::format("\"{}\" is not a direction (up, down, fwd, rev, +, -)", fd.text));
    const CsvField& fv = csv.field(col[3], "reading");
    const auto value = csv.number(fv, "reading");
    if (!value) csv.fail(fv.column, "reading", "the reading is empty");
    r.value = *value * factor;
    const auto key = std::make_tuple(std::llround(r.target_mm / kSameTargetMm), r.run, r.dir);
    const auto [it, fresh] = seen.emplace(key, r.line);
    if (!fresh)
      csv.fail(fr.column, "run",
               fmt::format("target {} run {} {} is already on line {}", ft.text, r.run,
                           r.dir > 0 ? "up" : "down", it->second));
    d.readings.push_back(r);
  }
  if (d.readings.empty())
    throw InputError({file, 0, 0, "reading", ""}, "the export has no readings");
  if (d.reference_mm) {
    bool found = false;
    for (const LaserReading& r : d.readings)
      found = found || std::abs(r.target_mm - *d.reference_mm) <= kSameTargetMm;
    if (!found)
      fail_at(file, reference, "reference",
              fmt::format("the reference {} mm is none of the targets", reference.value));
  }
  return d;
}

LaserExport load_laser_export(const std::string& path) {
  return read_input(path, "laser export", read_laser_export);
}

std::vector<LaserExport> read_laser_exports(std::istream& in, const std::string& file) {
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The lines, and where each section starts (index of its first line).
  std::vector<std::string> lines;
  {
    std::size_t pos = 0;
    while (pos <= text.size()) {
      std::size_t end = text.find('\n', pos);
      if (end == std::string::npos) end = text.size();
      lines.push_back(text.substr(pos, end - pos));
      pos = end + 1;
    }
  }
  std::vector<std::size_t> starts{0};
  bool data_seen = false;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::string l = lines[i];
    if (i == 0 && l.compare(0, 3, "\xEF\xBB\xBF") == 0) l.erase(0, 3);
    if (is_metadata_line(l)) {
      if (data_seen) starts.push_back(i);
      data_seen = false;
      continue;
    }
    const auto first = l.find_first_not_of(" \t\r");
    if (first != std::string::npos && l[first] != '#') data_seen = true;
  }
  // Each section read on its own: the other sections' lines left empty, so
  // the line numbers are those of the file.
  std::vector<LaserExport> out;
  for (std::size_t s = 0; s < starts.size(); ++s) {
    const std::size_t end = s + 1 < starts.size() ? starts[s + 1] : lines.size();
    std::string section;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (i >= starts[s] && i < end) section += lines[i];
      if (i + 1 < lines.size()) section += '\n';
    }
    std::istringstream one(section);
    LaserExport d = read_laser_export(one, file);
    for (const LaserExport& e : out)
      if (e.component == d.component) {
        std::size_t line = 0;
        for (std::size_t i = starts[s]; i < end && line == 0; ++i) {
          const auto hash = lines[i].find('#');
          if (is_metadata_line(lines[i]) &&
              lower(trim(lines[i].substr(hash + 1, lines[i].find(':') - hash - 1))) == "component")
            line = i + 1;
        }
        throw InputError({file, line, 0, "component", line ? lines[line - 1] : ""},
                         fmt::format("{} is already the component of an earlier section (one "
                                     "section per component)",
                                     d.component));
      }
    out.push_back(std::move(d));
  }
  return out;
}

std::vector<LaserExport> load_laser_exports(const std::string& path) {
  return read_input(path, "laser export", read_laser_exports);
}

namespace {
void append_runs(std::string& out, const LaserExport& data) {
  for (const LaserReading& r : data.readings)
    out += fmt::format("{},{},{},{},{},{}\n", data.axis, data.component, r.target_mm, r.run,
                       r.dir > 0 ? "up" : "down", r.value);
}
constexpr const char* kRunsHeader = "axis,component,target_mm,run,direction,deviation\n";
constexpr const char* kTableHeader = "axis,component,position_mm,direction,value,uncertainty\n";
}  // namespace

std::string laser_runs_csv(const LaserExport& data) {
  std::string out = kRunsHeader;
  append_runs(out, data);
  return out;
}

std::string laser_runs_csv(const std::vector<LaserExport>& sections) {
  std::string out = kRunsHeader;
  for (const LaserExport& d : sections) append_runs(out, d);
  return out;
}

std::string laser_table_csv(const std::vector<LaserExport>& sections) {
  std::string out = kTableHeader;
  for (const LaserExport& d : sections) out += laser_table_csv(d).substr(std::strlen(kTableHeader));
  return out;
}

std::string laser_table_csv(const LaserExport& data) {
  // Targets in ascending order, one per cluster within 1 nm.
  std::vector<const LaserReading*> sorted;
  for (const LaserReading& r : data.readings) sorted.push_back(&r);
  std::stable_sort(sorted.begin(), sorted.end(), [](const LaserReading* a, const LaserReading* b) {
    return a->target_mm < b->target_mm;
  });
  struct Stats {
    std::size_t n = 0;
    double sum = 0.0, sum2 = 0.0;
    std::size_t line = 0;
  };
  struct Target {
    double mm = 0.0;
    Stats up, down;
  };
  std::vector<Target> targets;
  bool any_up = false, any_down = false;
  for (const LaserReading* r : sorted) {
    if (targets.empty() || r->target_mm - targets.back().mm > kSameTargetMm)
      targets.push_back({r->target_mm, {}, {}});
    Stats& s = r->dir > 0 ? targets.back().up : targets.back().down;
    ++s.n;
    s.sum += r->value;
    s.sum2 += r->value * r->value;
    s.line = r->line;
    (r->dir > 0 ? any_up : any_down) = true;
  }
  auto mean_u = [&](const Stats& s, double target, const char* dir) {
    if (s.n < 2)
      throw InputError({data.file, s.line, 0, "run", ""},
                       fmt::format("target {} mm has {} run(s) {}: the table's uncertainty (s/√n) "
                                   "needs at least 2",
                                   target, s.n, dir));
    const double n = static_cast<double>(s.n);
    const double mean = s.sum / n;
    const double var = std::max(0.0, (s.sum2 - n * mean * mean) / (n - 1.0));
    return std::make_pair(mean, std::sqrt(var / n));
  };
  std::string out = kTableHeader;
  for (const Target& t : targets) {
    if (any_up && any_down) {
      const auto [mu, uu] = mean_u(t.up, t.mm, "up");
      const auto [md, ud] = mean_u(t.down, t.mm, "down");
      out += fmt::format("{},{},{},fwd,{},{}\n", data.axis, data.component, t.mm, mu, uu);
      out += fmt::format("{},{},{},rev,{},{}\n", data.axis, data.component, t.mm, md, ud);
    } else {
      const auto [m, u] = mean_u(any_up ? t.up : t.down, t.mm, any_up ? "up" : "down");
      out += fmt::format("{},{},{},mean,{},{}\n", data.axis, data.component, t.mm, m, u);
    }
  }
  return out;
}

}  // namespace abbe::io
