// Per-joint compensation tables for LinuxCNC (`abbe export linuxcnc`,
// docs/export.md): the positioning error of each axis along its own
// direction over its travel, at one tool point, as COMP_FILE_TYPE 1 files.
//
// LinuxCNC's reader (facts from its documentation and motion code): each
// line is "nominal forward reverse" read with three %lf; the first line that
// is not three numbers ends the file (so no comments); nominal positions
// must increase; at most 256 entries per joint; with type 1 the second and
// third values are trims in machine units that the motion controller adds
// to the commanded joint position (forward when the joint moves +, reverse
// when it moves −), interpolated linearly between the entries and held
// constant beyond the first and last entry.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <system_error>

#include "abbe/compensate/controller_tables.hpp"
#include "abbe/compensate/provenance.hpp"
#include "abbe/io/atomic_file.hpp"
#include "abbe/io/fixed6.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/machine/travel_check.hpp"
#include "abbe/pipeline/model_set.hpp"

namespace abbe::compensate {
namespace {

constexpr double kDefaultJointStepMm = 5.0;

// The value of the piecewise-linear (nominal, value) table at s, constant
// beyond the ends.
double interpolate(const std::vector<double>& s_mm, const std::vector<double>& v, double s) {
  if (s_mm.empty()) return 0.0;
  if (s <= s_mm.front()) return v.front();
  if (s >= s_mm.back()) return v.back();
  const auto it = std::upper_bound(s_mm.begin(), s_mm.end(), s);
  const auto i = static_cast<std::size_t>(it - s_mm.begin()) - 1;
  const double t = (s - s_mm[i]) / (s_mm[i + 1] - s_mm[i]);
  return v[i] + t * (v[i + 1] - v[i]);
}

const char* file_name(machine::Axis a) {
  return a == machine::Axis::x ? "x.comp" : a == machine::Axis::y ? "y.comp" : "z.comp";
}

}  // namespace

Eigen::Vector3d travel_centre_tip(const machine::Machine& machine, double tool_length) {
  Eigen::Vector3d p;
  for (machine::Axis a : machine::kAxes)
    p[machine::index(a)] = 0.5 * (machine.travel(a).min + machine.travel(a).max);
  p.z() -= tool_length;
  return p;
}

double JointTable::correction_um(double s, int direction) const {
  if (direction > 0) return -interpolate(nominal_mm, forward_um, s);
  if (direction < 0) return -interpolate(nominal_mm, reverse_um, s);
  return -0.5 * (interpolate(nominal_mm, forward_um, s) + interpolate(nominal_mm, reverse_um, s));
}

bool JointTable::direction_dependent() const {
  for (std::size_t i = 0; i < forward_um.size(); ++i)
    if (std::abs(forward_um[i] - reverse_um[i]) > 5e-7) return true;  // below the 1e-6 print
  return false;
}

std::array<JointTable, 3> joint_tables(const machine::Machine& machine,
                                       const JointTableOptions& options) {
  const std::string outside =
      machine::TravelCheck(machine.spec().travel).describe(options.at_tip, options.tool_length);
  if (!options.at_tip.allFinite() || !std::isfinite(options.tool_length) || !outside.empty())
    throw InputError({"<command line>", 0, 0, "--at", ""},
                     fmt::format("the tool point ({}, {}, {}) mm with tool length {} mm is not "
                                 "inside the travel{}",
                                 options.at_tip.x(), options.at_tip.y(), options.at_tip.z(),
                                 options.tool_length, outside.empty() ? "" : ": " + outside));
  pipeline::ModelSet models(machine, {options.model}, options.extension);
  const Eigen::Vector3d at_axes = options.at_tip + Eigen::Vector3d(0.0, 0.0, options.tool_length);
  std::array<JointTable, 3> out;
  for (machine::Axis a : machine::kAxes) {
    const auto j = static_cast<std::size_t>(machine::index(a));
    const machine::Travel& t = machine.travel(a);
    double step = options.step;
    if (step == 0.0) {  // the default: 5 mm, wider where the travel needs more entries
      step = std::max(kDefaultJointStepMm,
                      (t.max - t.min) / static_cast<double>(kLinuxCncMaxEntries - 1));
    }
    JointTable& table = out[j];
    table.axis = a;
    table.nominal_mm = regular_positions(t.min, t.max, step, 0, kLinuxCncMaxEntries, "--step");
    for (double s : table.nominal_mm) {
      Eigen::Vector3d axes = at_axes;
      axes[static_cast<Eigen::Index>(j)] = s;
      model::EvalPoint p;
      p.p = axes - Eigen::Vector3d(0.0, 0.0, options.tool_length);
      p.tool_length = options.tool_length;
      for (int dir : {1, -1}) {
        p.dir = {0, 0, 0};
        p.dir[j] = static_cast<std::int8_t>(dir);
        models.evaluate(p, machine.spec().file, 0);
        const double e = models.deviations()[0].e_um[static_cast<Eigen::Index>(j)];
        (dir > 0 ? table.forward_um : table.reverse_um).push_back(e);
      }
    }
  }
  return out;
}

std::string linuxcnc_comp_text(const JointTable& table, bool inch) {
  const double unit_mm = inch ? 25.4 : 1.0;
  fmt::memory_buffer b;
  for (std::size_t i = 0; i < table.nominal_mm.size(); ++i) {
    io::append_fixed6(b, table.nominal_mm[i] / unit_mm);
    b.push_back(' ');
    io::append_fixed6(b, -table.forward_um[i] * 1e-3 / unit_mm);
    b.push_back(' ');
    io::append_fixed6(b, -table.reverse_um[i] * 1e-3 / unit_mm);
    b.push_back('\n');
  }
  return fmt::to_string(b);
}

std::string linuxcnc_ini_text(const machine::Machine& machine, const JointTableOptions& options,
                              const std::array<JointTable, 3>& tables) {
  std::string s = "# abbe export linuxcnc: per-joint compensation (docs/export.md)\n";
  s += fmt::format("# machine: {}\n", machine.name());
  for (const FileFingerprint& f : machine_fingerprints(machine))
    s += fmt::format("# {} sha256={} {}\n", f.role, f.sha256, f.path);
  s += fmt::format("# model: {}{}\n", model::to_string(options.model),
                   options.extension ? " with an overlay (--extend)" : "");
  s += fmt::format(
      "# tool point: tip at X{:.4f} Y{:.4f} Z{:.4f} mm (machine coordinates), tool length "
      "{:.4f} mm\n",
      options.at_tip.x(), options.at_tip.y(), options.at_tip.z(), options.tool_length);
  s += fmt::format(
      "# positions and trims in {0}: [TRAJ] LINEAR_UNITS must be {0}, joint positions the\n"
      "# machine file's axis positions (same zero and direction)\n",
      options.inch ? "inch" : "mm");
  for (const JointTable& t : tables)
    s += fmt::format("# {}: {} entries, {}\n", machine::axis_letter(t.axis), t.nominal_mm.size(),
                     t.direction_dependent()
                         ? "forward and reverse differ (direction-dependent terms)"
                         : "forward = reverse (the model has no direction-dependent terms here)");
  for (const JointTable& t : tables)
    s += fmt::format("\n[JOINT_{}]\nCOMP_FILE = {}\nCOMP_FILE_TYPE = 1\n", machine::index(t.axis),
                     file_name(t.axis));
  return s;
}

std::string export_linuxcnc(const machine::Machine& machine, const JointTableOptions& options,
                            const std::string& dir) {
  const std::array<JointTable, 3> tables = joint_tables(machine, options);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw InputError({dir, 0, 0, "-o", ""}, fmt::format("cannot create the output directory: {}",
                                                        ec ? ec.message() : "not a directory"));
  const std::filesystem::path base(dir);
  auto write = [&](const std::string& name, const std::string& text) {
    io::AtomicOutputFile f((base / name).string());
    f.write(text.data(), text.size());
    f.commit();
  };
  for (const JointTable& t : tables) write(file_name(t.axis), linuxcnc_comp_text(t, options.inch));
  const std::string ini = linuxcnc_ini_text(machine, options, tables);
  write("linuxcnc.ini", ini);
  std::string summary = ini + "\n";
  for (const JointTable& t : tables) {
    double lo = 0.0, hi = 0.0;
    for (std::size_t i = 0; i < t.nominal_mm.size(); ++i) {
      lo = std::min({lo, -t.forward_um[i], -t.reverse_um[i]});
      hi = std::max({hi, -t.forward_um[i], -t.reverse_um[i]});
    }
    summary +=
        fmt::format("# {}: trims from {:.3f} to {:.3f} µm, written to {}\n",
                    machine::axis_letter(t.axis), lo, hi, (base / file_name(t.axis)).string());
  }
  return summary;
}

}  // namespace abbe::compensate
