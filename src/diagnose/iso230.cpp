#include "abbe/diagnose/iso230.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <utility>

#include "abbe/io/csv_reader.hpp"
#include "abbe/io/input_error.hpp"

namespace abbe::diagnose {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const char* const kColumns[] = {"axis", "component", "target_mm", "run", "direction", "deviation"};

[[noreturn]] void fail(const std::string& file, std::size_t line, std::size_t column,
                       const std::string& field, const std::string& source,
                       const std::string& message) {
  SourceLocation where;
  where.file = file;
  where.line = line;
  where.column = column;
  where.field = field;
  where.source_line = source;
  throw InputError(where, message);
}

double mean_of(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

// Estimator of the standard uncertainty (n − 1 in the denominator).
double stddev_of(const std::vector<double>& v, double mean) {
  double s = 0.0;
  for (double x : v) s += (x - mean) * (x - mean);
  return std::sqrt(s / static_cast<double>(v.size() - 1));
}

}  // namespace

std::vector<Iso230Reading> read_iso230_runs(std::istream& in, const std::string& file) {
  // io::CsvReader: BOM, `,` `;` or tab, quotes, header names in any case, CRLF.
  io::CsvReader csv(in, file);
  csv.read_header();
  std::array<std::size_t, 6> index{};
  for (int c = 0; c < 6; ++c) {
    const auto at = csv.column(kColumns[c]);
    if (!at)
      csv.fail(1, kColumns[c],
               fmt::format("header lacks column '{}' (expected "
                           "axis,component,target_mm,run,direction,deviation)",
                           kColumns[c]));
    index[static_cast<std::size_t>(c)] = *at;
  }
  const std::size_t n_columns = csv.header_names().size();
  for (std::size_t i = 0; i < n_columns; ++i) {
    const std::string& name = csv.header_names()[i];
    if (std::find(std::begin(kColumns), std::end(kColumns), name) == std::end(kColumns))
      csv.fail(csv.fields()[i].column, name, fmt::format("unknown column '{}'", name));
  }
  std::vector<Iso230Reading> out;
  while (csv.next()) {
    const std::vector<io::CsvField>& cells = csv.fields();
    if (cells.size() != n_columns)
      csv.fail(1, "", fmt::format("expected {} fields, found {}", n_columns, cells.size()));
    auto cell = [&](int c) -> const io::CsvField& {
      return cells[index[static_cast<std::size_t>(c)]];
    };
    auto number = [&](int c) {
      const io::CsvField& x = cell(c);
      const auto v = io::parse_csv_number(x.text);
      if (!v) csv.fail(x.column, kColumns[c], fmt::format("'{}' is not a number", x.text));
      return *v;
    };
    Iso230Reading r;
    r.line = csv.line();
    const io::CsvField& axis = cell(0);
    if (axis.text != "X" && axis.text != "Y" && axis.text != "Z")
      csv.fail(axis.column, "axis", fmt::format("axis '{}' is not X, Y or Z", axis.text));
    r.axis = axis.text[0];
    const io::CsvField& comp = cell(1);
    const std::string dirs = "XYZABC";
    if (comp.text.size() != 3 || comp.text[0] != 'E' ||
        dirs.find(comp.text[1]) == std::string::npos || comp.text[2] != r.axis)
      csv.fail(comp.column, "component",
               fmt::format("component '{}' is not a component of axis {} (EX{}, EY{}, …, EC{})",
                           comp.text, r.axis, r.axis, r.axis, r.axis));
    r.component = std::string(comp.text);
    r.target_mm = number(2);
    const double run = number(3);
    if (run < 1.0 || run != std::floor(run) || run > 1e6)
      csv.fail(cell(3).column, "run",
               fmt::format("run '{}' is not a positive integer", cell(3).text));
    r.run = static_cast<int>(run);
    const std::string_view d = cell(4).text;
    if (d == "up" || d == "fwd")
      r.dir = +1;
    else if (d == "down" || d == "rev")
      r.dir = -1;
    else
      csv.fail(cell(4).column, "direction",
               fmt::format("direction '{}' is not up, down, fwd or rev", d));
    r.deviation = number(5);
    out.push_back(r);
  }
  if (out.empty()) csv.fail(0, "", "no runs after the header");
  return out;
}

std::vector<Iso230Result> evaluate_iso230(const std::vector<Iso230Reading>& readings,
                                          const std::string& file) {
  // Group by component (first appearance order), then by target (rounded to 1 nm).
  std::vector<std::string> order;
  struct Group {
    std::map<long long, std::array<std::map<int, const Iso230Reading*>, 2>> by_target;
  };
  std::map<std::string, Group> groups;
  for (const Iso230Reading& r : readings) {
    const std::string key = r.component;
    if (!groups.count(key)) order.push_back(key);
    auto& slot = groups[key].by_target[std::llround(r.target_mm * 1e6)][r.dir > 0 ? 0 : 1];
    if (!slot.emplace(r.run, &r).second)
      fail(file, r.line, 0, "run", "",
           fmt::format("{} target {} run {} {} appears twice", r.component, r.target_mm, r.run,
                       r.dir > 0 ? "up" : "down"));
  }
  std::vector<Iso230Result> results;
  for (const std::string& key : order) {
    const Group& g = groups[key];
    Iso230Result res;
    res.axis = key[2];
    res.component = key;
    res.unit = (key[1] == 'A' || key[1] == 'B' || key[1] == 'C') ? "urad" : "um";
    for (const auto& [t, dirs] : g.by_target) {
      res.has_up = res.has_up || !dirs[0].empty();
      res.has_down = res.has_down || !dirs[1].empty();
    }
    res.runs = std::numeric_limits<int>::max();
    for (const auto& [t, dirs] : g.by_target) {
      Iso230Target tg;
      tg.target_mm = static_cast<double>(t) * 1e-6;
      for (int d = 0; d < 2; ++d) {
        const bool used = d == 0 ? res.has_up : res.has_down;
        if (!used) continue;
        const auto& runs = dirs[static_cast<std::size_t>(d)];
        if (runs.size() < 2)
          fail(file, runs.empty() ? 0 : runs.begin()->second->line, 0, "run", "",
               fmt::format("{} target {}: {} {} run(s); the evaluation needs at least 2 per "
                           "direction (ISO 230-2 asks for 5)",
                           key, tg.target_mm, runs.size(), d == 0 ? "up" : "down"));
        std::vector<double> v;
        for (const auto& [run, r] : runs) v.push_back(r->deviation);
        const double m = mean_of(v), s = stddev_of(v, m);
        (d == 0 ? tg.n_up : tg.n_down) = static_cast<int>(v.size());
        (d == 0 ? tg.mean_up : tg.mean_down) = m;
        (d == 0 ? tg.s_up : tg.s_down) = s;
        res.runs = std::min(res.runs, static_cast<int>(v.size()));
      }
      if (!res.has_up) tg.mean_up = tg.s_up = kNaN;
      if (!res.has_down) tg.mean_down = tg.s_down = kNaN;
      if (res.has_up && res.has_down) {
        tg.reversal = tg.mean_up - tg.mean_down;
        tg.mean = 0.5 * (tg.mean_up + tg.mean_down);
        tg.repeatability = std::max({2.0 * tg.s_up + 2.0 * tg.s_down + std::abs(tg.reversal),
                                     4.0 * tg.s_up, 4.0 * tg.s_down});
      } else {
        tg.reversal = kNaN;
        tg.mean = res.has_up ? tg.mean_up : tg.mean_down;
        tg.repeatability = kNaN;
      }
      res.targets.push_back(tg);
    }
    // Per-direction values.
    auto unidirectional = [&](bool up, double& A, double& R, double& E) {
      if (!(up ? res.has_up : res.has_down)) {
        A = R = E = kNaN;
        return;
      }
      double max_m = -INFINITY, min_m = INFINITY, max_a = -INFINITY, min_a = INFINITY;
      R = 0.0;
      for (const Iso230Target& t : res.targets) {
        const double m = up ? t.mean_up : t.mean_down, s = up ? t.s_up : t.s_down;
        max_m = std::max(max_m, m);
        min_m = std::min(min_m, m);
        max_a = std::max(max_a, m + 2.0 * s);
        min_a = std::min(min_a, m - 2.0 * s);
        R = std::max(R, 4.0 * s);
      }
      E = max_m - min_m;
      A = max_a - min_a;
    };
    unidirectional(true, res.A_up, res.R_up, res.E_up);
    unidirectional(false, res.A_down, res.R_down, res.E_down);
    if (res.has_up && res.has_down) {
      double max_m = -INFINITY, min_m = INFINITY, max_a = -INFINITY, min_a = INFINITY;
      double max_x = -INFINITY, min_x = INFINITY, sum_b = 0.0;
      res.B = res.R = 0.0;
      for (const Iso230Target& t : res.targets) {
        max_m = std::max({max_m, t.mean_up, t.mean_down});
        min_m = std::min({min_m, t.mean_up, t.mean_down});
        max_a = std::max({max_a, t.mean_up + 2.0 * t.s_up, t.mean_down + 2.0 * t.s_down});
        min_a = std::min({min_a, t.mean_up - 2.0 * t.s_up, t.mean_down - 2.0 * t.s_down});
        max_x = std::max(max_x, t.mean);
        min_x = std::min(min_x, t.mean);
        res.B = std::max(res.B, std::abs(t.reversal));
        sum_b += t.reversal;
        res.R = std::max(res.R, t.repeatability);
      }
      res.E = max_m - min_m;
      res.A = max_a - min_a;
      res.M = max_x - min_x;
      res.B_mean = sum_b / static_cast<double>(res.targets.size());
    } else {
      res.A = res.R = res.B = res.B_mean = res.E = res.M = kNaN;
    }
    results.push_back(std::move(res));
  }
  return results;
}

namespace {
nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}
}  // namespace

std::string iso230_to_json(const std::vector<Iso230Result>& results, bool per_target) {
  nlohmann::json out = nlohmann::json::array();
  for (const Iso230Result& r : results) {
    nlohmann::json j;
    j["axis"] = std::string(1, r.axis);
    j["component"] = r.component;
    j["unit"] = r.unit;
    j["n_targets"] = r.targets.size();
    j["runs"] = r.runs;
    j["bidirectional"] = r.has_up && r.has_down;
    const std::pair<const char*, double> parameters[] = {
        {"A", r.A},       {"A_up", r.A_up},     {"A_down", r.A_down}, {"R", r.R},
        {"R_up", r.R_up}, {"R_down", r.R_down}, {"B", r.B},           {"B_mean", r.B_mean},
        {"E", r.E},       {"E_up", r.E_up},     {"E_down", r.E_down}, {"M", r.M}};
    for (const auto& [key, value] : parameters) j[key] = number_or_null(value);
    if (per_target) {
      nlohmann::json ts = nlohmann::json::array();
      for (const Iso230Target& t : r.targets)
        ts.push_back({{"target_mm", t.target_mm},
                      {"mean_up", number_or_null(t.mean_up)},
                      {"mean_down", number_or_null(t.mean_down)},
                      {"s_up", number_or_null(t.s_up)},
                      {"s_down", number_or_null(t.s_down)},
                      {"B", number_or_null(t.reversal)},
                      {"R", number_or_null(t.repeatability)}});
      j["targets"] = ts;
    }
    out.push_back(j);
  }
  return nlohmann::json{{"iso230", out}}.dump(2) + "\n";
}

std::string iso230_to_text(const std::vector<Iso230Result>& results) {
  auto f = [](double v) {
    return std::isfinite(v) ? fmt::format("{:9.3f}", v) : std::string(9, ' ').replace(8, 1, "-");
  };
  std::string out =
      fmt::format("{:<4} {:<5} {:>4} {:>7} {:>4} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}\n", "axis",
                  "comp", "unit", "targets", "runs", "A", "R", "B_mean", "M", "B", "E");
  // The text spells units as the docs do (µm, µrad); JSON keeps its ASCII ids.
  auto shown = [](const std::string& unit) {
    return unit == "um" ? std::string("µm") : unit == "urad" ? std::string("µrad") : unit;
  };
  for (const Iso230Result& r : results)
    out += fmt::format("{:<4} {:<5} {:>4} {:>7} {:>4} {} {} {} {} {} {}\n", r.axis, r.component,
                       shown(r.unit), r.targets.size(), r.runs, f(r.A), f(r.R), f(r.B_mean), f(r.M),
                       f(r.B), f(r.E));
  return out;
}

}  // namespace abbe::diagnose
