#include "abbe/machine/component_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "abbe/io/csv_reader.hpp"
#include "abbe/io/input_error.hpp"

namespace abbe::machine {

namespace {

// The sixth column, `uncertainty`, is optional.
constexpr std::array<std::string_view, 6> kColumns{"axis",      "component", "position_mm",
                                                   "direction", "value",     "uncertainty"};

}  // namespace

const char* to_string(TableDirection d) {
  switch (d) {
    case TableDirection::fwd:
      return "fwd";
    case TableDirection::rev:
      return "rev";
    case TableDirection::mean:
      return "mean";
  }
  return "?";
}

ComponentTable ComponentTable::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, 0, 0, "", ""}, "cannot open the component table");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse(buffer.str(), path);
}

ComponentTable ComponentTable::parse(const std::string& text, const std::string& file) {
  ComponentTable table;
  table.file_ = file;
  table.slot_.fill(0);

  // io::CsvReader: BOM, `,` `;` or tab, quotes, header names in any case,
  // CRLF, `#` comment lines.
  std::istringstream in(text);
  io::CsvReader csv(in, file, io::CsvReader::Options{'#'});
  csv.read_header();
  const std::size_t columns =
      csv.header_names().size() == kColumns.size() && csv.header_names().back() == kColumns.back()
          ? kColumns.size()
          : kColumns.size() - 1;
  table.has_uncertainty_ = columns == kColumns.size();
  for (std::size_t i = 0; i < csv.header_names().size() || i < columns; ++i)
    if (i >= csv.header_names().size() || i >= columns || csv.header_names()[i] != kColumns[i])
      csv.fail(i < csv.fields().size() ? csv.fields()[i].column : 1, "header",
               "the header must be \"axis,component,position_mm,direction,value\" (optionally "
               "followed by \",uncertainty\")");
  auto error = [&](std::size_t column, std::string_view field, const std::string& msg) {
    csv.fail(column, field, msg);
  };

  while (csv.next()) {
    const std::size_t line_no = csv.line();
    const std::vector<io::CsvField>& fields = csv.fields();
    const std::size_t n = fields.size();
    if (n > columns) error(fields[columns].column, "", fmt::format("more than {} fields", columns));
    if (n != columns)
      error(csv.line_text().size() + 1, kColumns[n],
            fmt::format("{} fields instead of {}", n, columns));

    auto axis = parse_axis(fields[0].text);
    if (!axis)
      error(fields[0].column, "axis",
            fmt::format("unknown axis \"{}\" (expected X, Y or Z)", fields[0].text));
    auto comp = parse_component(fields[1].text);
    if (!comp) {
      std::string hint;
      if (fields[1].text == "EC0Y" || fields[1].text == "EB0Z" || fields[1].text == "EA0Z")
        hint = " (squareness belongs in the machine file's `squareness`, not in the table)";
      error(fields[1].column, "component",
            fmt::format("unknown component \"{}\"; components of axis j are EXj, EYj, EZj, EAj, "
                        "EBj, ECj{}",
                        fields[1].text, hint));
    }
    if (comp->axis != *axis)
      error(fields[1].column, "component",
            fmt::format("component {} belongs to axis {}, not {}", fields[1].text,
                        axis_letter(comp->axis), axis_letter(*axis)));
    double position = 0.0, value = 0.0, u = 0.0;
    for (int f : {2, 4, 5}) {
      if (static_cast<std::size_t>(f) >= columns) break;
      const io::CsvField& fld = fields[static_cast<std::size_t>(f)];
      double& out = f == 2 ? position : f == 4 ? value : u;
      const char* b = fld.text.data();
      const char* e = b + fld.text.size();
      if (b != e && *b == '+') ++b;
      auto [ptr, ec] = std::from_chars(b, e, out);
      if (fld.text.empty() || ec != std::errc() || ptr != e)
        error(fld.column, kColumns[static_cast<std::size_t>(f)],
              fmt::format("\"{}\" is not a number", fld.text));
      if (!std::isfinite(out))
        error(fld.column, kColumns[static_cast<std::size_t>(f)],
              fmt::format("{} must be finite", kColumns[static_cast<std::size_t>(f)]));
    }
    if (u < 0.0)
      error(fields[5].column, "uncertainty",
            fmt::format("the standard uncertainty {} is negative", fields[5].text));
    TableDirection dir = TableDirection::mean;
    if (fields[3].text == "fwd")
      dir = TableDirection::fwd;
    else if (fields[3].text == "rev")
      dir = TableDirection::rev;
    else if (fields[3].text == "mean")
      dir = TableDirection::mean;
    else
      error(fields[3].column, "direction",
            fmt::format("direction \"{}\" is not one of fwd, rev, mean", fields[3].text));

    // Mean and fwd/rev are exclusive for one component.
    bool is_mean = dir == TableDirection::mean;
    for (TableDirection other : {TableDirection::fwd, TableDirection::rev, TableDirection::mean}) {
      bool other_mean = other == TableDirection::mean;
      if (is_mean != other_mean && table.slot_[slot(*comp, other)] != 0) {
        const auto& s =
            table.series_[static_cast<std::size_t>(table.slot_[slot(*comp, other)] - 1)];
        error(fields[3].column, "direction",
              fmt::format("{} of axis {} mixes `mean` with `fwd`/`rev` rows (line {} has `{}`): "
                          "give either one mean series or both fwd and rev",
                          fields[1].text, fields[0].text, s.line.front(), to_string(other)));
      }
    }

    int& sl = table.slot_[slot(*comp, dir)];
    if (sl == 0) {
      table.series_.push_back(ComponentSeries{*comp, dir, {}, {}, {}, {}});
      sl = static_cast<int>(table.series_.size());
    }
    ComponentSeries& s = table.series_[static_cast<std::size_t>(sl - 1)];
    if (!s.position_mm.empty() && position <= s.position_mm.back())
      error(fields[2].column, "position_mm",
            fmt::format("position {} of {} {} is {} the previous one ({} on line {}); positions "
                        "must be strictly increasing per axis, component and direction",
                        fields[2].text, fields[1].text, fields[3].text,
                        position == s.position_mm.back() ? "a duplicate of" : "below",
                        s.position_mm.back(), s.line.back()));
    s.position_mm.push_back(position);
    s.value.push_back(value);
    s.line.push_back(line_no);
    if (table.has_uncertainty_) s.u.push_back(u);
  }

  // Whole-series checks: bidirectional pairs complete, units plausible.
  for (const ComponentSeries& s : table.series_) {
    std::string name = component_name(s.id);
    if (s.direction != TableDirection::mean) {
      TableDirection other =
          s.direction == TableDirection::fwd ? TableDirection::rev : TableDirection::fwd;
      if (table.slot_[slot(s.id, other)] == 0)
        throw InputError({file, s.line.front(), 0, "direction", ""},
                         fmt::format("{} has `{}` rows but no `{}` rows: a bidirectional "
                                     "component needs both (or give one `mean` series)",
                                     name, to_string(s.direction), to_string(other)));
    }
    std::size_t imax = 0;
    for (std::size_t i = 0; i < s.value.size(); ++i)
      if (std::abs(s.value[i]) > std::abs(s.value[imax])) imax = i;
    double vmax = std::abs(s.value[imax]);
    double span = s.position_mm.back() - s.position_mm.front();
    if (s.id.linear() && vmax > 0.0 && vmax < kMinLinearMaxUm && span > kUnitCheckSpanMm)
      throw InputError(
          {file, s.line[imax], 0, "value", ""},
          fmt::format("{} {}: the largest |value| is {} µm over {} mm of travel — this looks "
                      "like mm; linear components are in µm (unit check: 0 < max|value| < {} µm "
                      "over more than {} mm)",
                      name, to_string(s.direction), vmax, span, kMinLinearMaxUm, kUnitCheckSpanMm));
    if (!s.id.linear() && vmax > kMaxAngularUrad)
      throw InputError({file, s.line[imax], 0, "value", ""},
                       fmt::format("{} {}: |value| = {} µrad is implausibly large (unit check: "
                                   "angular components are in µrad and must stay within {} µrad)",
                                   name, to_string(s.direction), vmax, kMaxAngularUrad));
  }
  return table;
}

const ComponentSeries* ComponentTable::find(ComponentId id, TableDirection d) const {
  int sl = slot_[slot(id, d)];
  return sl == 0 ? nullptr : &series_[static_cast<std::size_t>(sl - 1)];
}

bool ComponentTable::has(ComponentId id) const {
  return find(id, TableDirection::mean) || find(id, TableDirection::fwd);
}

bool ComponentTable::bidirectional(ComponentId id) const {
  return find(id, TableDirection::fwd) != nullptr;
}

bool ComponentTable::axis_has_components(Axis a) const {
  for (int d = 0; d < kComponentsPerAxis; ++d)
    if (has(ComponentId{a, d})) return true;
  return false;
}

ComponentTable ComponentTable::with_values(const std::vector<std::vector<double>>& values) const {
  if (values.size() != series_.size())
    throw std::invalid_argument("with_values: another number of series");
  ComponentTable t = *this;
  for (std::size_t i = 0; i < series_.size(); ++i) {
    if (values[i].size() != series_[i].value.size())
      throw std::invalid_argument("with_values: another number of values");
    t.series_[i].value = values[i];
  }
  return t;
}

}  // namespace abbe::machine
