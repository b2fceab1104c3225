// Machine::load / Machine::parse: the YAML machine file (docs/formats.md).
// Every key is checked; errors name the file, the line (yaml-cpp Mark) and
// the field path, e.g. "machine.yaml:12:7 [axes.X.points.all]".
#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "home_positions_yaml.hpp"
#include "src/io/yaml_reader.hpp"

namespace abbe::machine {

namespace {

using Reader = io::YamlReader;

AxisRecord read_record(const Reader& r, const YAML::Node& node, Axis axis,
                       const std::string& field) {
  r.check_keys(node, field, {"measured_at", "points"});
  AxisRecord rec;
  rec.present = true;
  const YAML::Node at = r.required(node, "measured_at", field);
  std::string fat = field + ".measured_at";
  r.check_keys(at, fat, {"x", "y", "z", "tool_length"});
  rec.measured_tip = {r.number(r.required(at, "x", fat), fat + ".x"),
                      r.number(r.required(at, "y", fat), fat + ".y"),
                      r.number(r.required(at, "z", fat), fat + ".z")};
  rec.measured_tool_length = r.number(r.required(at, "tool_length", fat), fat + ".tool_length");

  const YAML::Node points = r.required(node, "points", field);
  std::string fp = field + ".points";
  std::set<std::string> allowed{"all"};
  for (int k = 0; k < 3; ++k) allowed.insert(component_name({axis, k}));
  r.expect_map(points, fp);
  for (const auto& kv : points) {
    std::string key = r.scalar_key(kv.first, fp);
    if (!allowed.count(key)) {
      auto id = parse_component(key);
      std::string why = !id ? "is not a component name"
                        : id->axis != axis
                            ? fmt::format("belongs to axis {}", axis_letter(id->axis))
                            : "is angular (angular errors need no measurement point)";
      r.fail(kv.first, Reader::join(fp, key),
             fmt::format("`{}` {}; allowed keys: {}", key, why, fmt::join(allowed, ", ")));
    }
  }
  std::optional<Eigen::Vector3d> all;
  if (points["all"]) all = r.vec3(points["all"], fp + ".all");
  for (int k = 0; k < 3; ++k) {
    std::string name = component_name({axis, k});
    if (points[name])
      rec.point[static_cast<std::size_t>(k)] = r.vec3(points[name], Reader::join(fp, name));
    else if (all)
      rec.point[static_cast<std::size_t>(k)] = *all;
    else
      r.fail(points, Reader::join(fp, name),
             fmt::format("no measurement point for {} (give `all` or `{}`)", name, name));
  }
  return rec;
}

// An optional mapping from a tool/H number (integer >= 0) to a length in mm
// (>= 0): tool_table (H -> tool length) and tool_diameters (T -> diameter).
std::map<int, double> read_tool_map(const Reader& r, const YAML::Node& root, const char* key_name,
                                    const char* number_kind, const char* value_kind) {
  std::map<int, double> out;
  const YAML::Node node = root[key_name];
  if (!node) return out;
  r.expect_map(node, key_name);
  for (const auto& kv : node) {
    const std::string key = r.scalar_key(kv.first, key_name);
    const std::string f = fmt::format("{}.{}", key_name, key);
    int number = 0;
    try {
      std::size_t used = 0;
      number = std::stoi(key, &used);
      if (used != key.size()) throw std::invalid_argument(key);
    } catch (const std::exception&) {
      r.fail(kv.first, f, fmt::format("`{}` is not {} (an integer)", key, number_kind));
    }
    if (number < 0) r.fail(kv.first, f, fmt::format("{} must not be negative", number_kind));
    const double value = r.number(kv.second, f);
    if (value < 0.0) r.fail(kv.second, f, fmt::format("{} must not be negative", value_kind));
    out[number] = value;
  }
  return out;
}

// A standard uncertainty: finite and not negative.
double read_u(const Reader& r, const YAML::Node& node, const std::string& field) {
  const double u = r.number(node, field);
  if (u < 0.0)
    r.fail(node, field, fmt::format("a standard uncertainty must not be negative (got {})", u));
  return u;
}

// The optional `uncertainty` key (docs/formats.md).
CampaignUncertainty read_uncertainty(const Reader& r, const YAML::Node& node) {
  const std::string f = "uncertainty";
  r.check_keys(node, f, {"laser", "components", "reflector_mm", "squareness"});
  CampaignUncertainty u;
  u.given = true;
  if (const YAML::Node laser = node["laser"]) {
    r.check_keys(laser, f + ".laser", {"constant_um", "ppm"});
    if (laser["constant_um"])
      u.laser_constant_um = read_u(r, laser["constant_um"], f + ".laser.constant_um");
    if (laser["ppm"]) u.laser_ppm = read_u(r, laser["ppm"], f + ".laser.ppm");
  }
  if (const YAML::Node comps = node["components"]) {
    const std::string fc = f + ".components";
    r.expect_map(comps, fc);
    for (const auto& kv : comps) {
      const std::string key = r.scalar_key(kv.first, fc);
      const auto id = parse_component(key);
      if (!id)
        r.fail(kv.first, Reader::join(fc, key),
               fmt::format("`{}` is not a component name (EXX … ECZ; squareness goes under "
                           "uncertainty.squareness)",
                           key));
      u.component[static_cast<std::size_t>(index(id->axis) * kComponentsPerAxis + id->d)] =
          read_u(r, kv.second, Reader::join(fc, key));
    }
  }
  if (const YAML::Node refl = node["reflector_mm"])
    u.reflector_mm = read_u(r, refl, f + ".reflector_mm");
  if (const YAML::Node sq = node["squareness"]) {
    r.check_keys(sq, f + ".squareness", {"EC0Y", "EB0Z", "EA0Z"});
    const char* names[3] = {"EC0Y", "EB0Z", "EA0Z"};
    for (std::size_t i = 0; i < 3; ++i)
      if (sq[names[i]])
        u.squareness_urad[i] = read_u(r, sq[names[i]], f + ".squareness." + names[i]);
  }
  return u;
}

bool read_flag(const Reader& r, const YAML::Node& node, const std::string& field) {
  const std::string v = r.string(node, field);
  if (v == "true") return true;
  if (v == "false") return false;
  r.fail(node, field, fmt::format("\"{}\" is not true or false", v));
}

// The optional `conventions` key (docs/formats.md), checked against the table.
ReferenceConventions read_conventions(const Reader& r, const YAML::Node& node,
                                      const ComponentTable& table) {
  const std::string f = "conventions";
  r.expect_map(node, f);
  ReferenceConventions rc;
  for (const auto& kv : node) {
    const std::string key = r.scalar_key(kv.first, f);
    const std::string fk = Reader::join(f, key);
    if (key == "squareness") {
      const std::string v = r.string(kv.second, fk);
      if (v != "same_reference" && v != "independent")
        r.fail(kv.second, fk, fmt::format("\"{}\" is not same_reference or independent", v));
      rc.squareness_same_reference = v == "same_reference";
      continue;
    }
    const auto id = parse_component(key);
    if (!id)
      r.fail(kv.first, fk,
             fmt::format("`{}` is not a component name (EXX … ECZ) nor `squareness`", key));
    const bool straightness = id->linear() && id->d != index(id->axis);
    r.check_keys(kv.second, fk,
                 id->linear() ? std::set<std::string>{"reference_mm", "slope_removed"}
                              : std::set<std::string>{"reference_mm", "relative"});
    ComponentConvention c;
    c.given = true;
    c.reference_mm = r.number(r.required(kv.second, "reference_mm", fk), fk + ".reference_mm");
    if (const YAML::Node sl = kv.second["slope_removed"]) {
      c.slope_removed = read_flag(r, sl, fk + ".slope_removed");
      if (c.slope_removed && !straightness)
        r.fail(sl, fk + ".slope_removed",
               fmt::format("{} is a positioning component: only straightness has a slope to "
                           "remove (a positioning slope is a scale error, not a convention)",
                           key));
    }
    if (const YAML::Node rel = kv.second["relative"])
      c.relative = read_flag(r, rel, fk + ".relative");
    if (!id->linear() && !c.relative)
      r.fail(kv.second, fk + ".relative",
             fmt::format("an angular convention is `relative: true` (absolute angles need no "
                         "entry)"));
    // The reference is one of the positions the component was measured at
    // (within its measured range).
    const ComponentSeries* s = table.find(*id, TableDirection::mean);
    if (!s) s = table.find(*id, TableDirection::fwd);
    const YAML::Node ref = kv.second["reference_mm"];
    if (!s)
      r.fail(ref, fk + ".reference_mm", fmt::format("the component table has no data for {}", key));
    if (c.reference_mm < s->position_mm.front() - 1e-6 ||
        c.reference_mm > s->position_mm.back() + 1e-6)
      r.fail(ref, fk + ".reference_mm",
             fmt::format("the reference {} mm lies outside the measured range of {} [{}, {}] mm",
                         c.reference_mm, key, s->position_mm.front(), s->position_mm.back()));
    rc.component[static_cast<std::size_t>(index(id->axis) * kComponentsPerAxis + id->d)] = c;
  }
  return rc;
}

}  // namespace

Machine Machine::load(const std::string& yaml_path) {
  std::ifstream in(yaml_path, std::ios::binary);
  if (!in) throw InputError({yaml_path, 0, 0, "", ""}, "cannot open the machine file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  std::filesystem::path base = std::filesystem::path(yaml_path).parent_path();
  return parse(buffer.str(), yaml_path, base.string());
}

Machine Machine::parse(const std::string& yaml_text, const std::string& file,
                       const std::string& base_dir) {
  const Reader r(file, yaml_text);
  const YAML::Node root = r.load(yaml_text);  // const: lookups never insert keys
  if (!root.IsMap()) r.fail(root, "", "a machine file is a YAML mapping (see docs/formats.md)");
  r.check_keys(root, "",
               {"name", "chain", "travel", "tool_length", "tool_table", "tool_diameters",
                "work_offsets", "home_positions", "squareness", "table", "out_of_range", "axes",
                "uncertainty", "conventions"});

  MachineSpec spec;
  spec.file = file;
  spec.name = r.string(r.required(root, "name", ""), "name");

  const YAML::Node chain = r.required(root, "chain", "");
  try {
    spec.chain = KinematicChain::parse(r.string(chain, "chain"));
  } catch (const std::invalid_argument& e) {
    r.fail(chain, "chain", e.what());
  }

  const YAML::Node travel = r.required(root, "travel", "");
  r.check_keys(travel, "travel", {"x", "y", "z"});
  for (Axis a : kAxes) {
    std::string key(1, static_cast<char>(std::tolower(axis_letter(a))));
    std::string f = "travel." + key;
    const YAML::Node t = r.required(travel, key, "travel");
    auto mm = r.numbers(t, f, 2);
    if (!(mm[0] < mm[1]))
      r.fail(t, f, fmt::format("travel min ({}) must be below max ({})", mm[0], mm[1]));
    spec.travel[static_cast<std::size_t>(index(a))] = {mm[0], mm[1]};
  }

  const YAML::Node tl = r.required(root, "tool_length", "");
  spec.tool_length = r.number(tl, "tool_length");
  if (spec.tool_length < 0.0) r.fail(tl, "tool_length", "the tool length must not be negative");

  spec.tool_table = read_tool_map(r, root, "tool_table", "an H number", "the tool length");
  spec.tool_diameters =
      read_tool_map(r, root, "tool_diameters", "a tool number", "the tool diameter");

  if (const YAML::Node wo = root["work_offsets"]) {
    r.check_keys(wo, "work_offsets", {"G54", "G55", "G56", "G57", "G58", "G59"});
    for (int g = 0; g < 6; ++g) {
      std::string key = fmt::format("G{}", 54 + g);
      if (wo[key])
        spec.work_offsets[static_cast<std::size_t>(g)] = r.vec3(wo[key], "work_offsets." + key);
    }
  }

  detail::parse_home_positions(r, root);  // validated here, read by read_home_positions

  if (const YAML::Node sq = root["squareness"]) {
    r.check_keys(sq, "squareness", {"EC0Y", "EB0Z", "EA0Z"});
    if (sq["EC0Y"]) spec.squareness.ec0y = r.number(sq["EC0Y"], "squareness.EC0Y");
    if (sq["EB0Z"]) spec.squareness.eb0z = r.number(sq["EB0Z"], "squareness.EB0Z");
    if (sq["EA0Z"]) spec.squareness.ea0z = r.number(sq["EA0Z"], "squareness.EA0Z");
  }

  if (const YAML::Node u = root["uncertainty"]) spec.uncertainty = read_uncertainty(r, u);

  if (const YAML::Node oor = root["out_of_range"]) {
    std::string p = r.string(oor, "out_of_range");
    if (p == "clamp")
      spec.out_of_range = OutOfRangePolicy::clamp;
    else if (p == "extrapolate")
      spec.out_of_range = OutOfRangePolicy::extrapolate;
    else if (p == "error")
      spec.out_of_range = OutOfRangePolicy::error;
    else
      r.fail(oor, "out_of_range", fmt::format("\"{}\" is not one of clamp, extrapolate, error", p));
  }

  const YAML::Node axes = root["axes"];
  if (axes) {
    r.check_keys(axes, "axes", {"X", "Y", "Z"});
    for (Axis a : kAxes) {
      std::string key(1, axis_letter(a));
      if (axes[key])
        spec.axes[static_cast<std::size_t>(index(a))] = read_record(r, axes[key], a, "axes." + key);
    }
  }

  const YAML::Node table = r.required(root, "table", "");
  std::string table_name = r.string(table, "table");
  std::filesystem::path tp(table_name);
  if (tp.is_relative() && !base_dir.empty()) tp = std::filesystem::path(base_dir) / tp;
  spec.table_file = tp.string();
  {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(tp, ec))
      r.fail(table, "table",
             fmt::format("cannot open the component table \"{}\" (resolved to {})", table_name,
                         spec.table_file));
  }
  spec.table = ComponentTable::load(spec.table_file);
  if (const YAML::Node conv = root["conventions"])
    spec.conventions = read_conventions(r, conv, spec.table);

  // Every axis with table data needs its measurement record (the arms).
  for (Axis a : kAxes) {
    if (spec.table.axis_has_components(a) &&
        !spec.axes[static_cast<std::size_t>(index(a))].present) {
      std::string f = fmt::format("axes.{}", axis_letter(a));
      r.fail(axes ? axes : root, f,
             fmt::format("the component table {} has errors of axis {} but the machine file has "
                         "no measurement record `{}` (measured_at, points) for it",
                         spec.table_file, axis_letter(a), f));
    }
  }
  return Machine(std::move(spec));
}

}  // namespace abbe::machine
