// abbe map: the volumetric error of a machine over its whole travel (or a
// box) on a grid, per error model: a CSV of the grid points, statistics per
// model (mean, RMS, max |d|), the htm vs ae-arm comparison of the AE-arm
// paper (mean |d| difference and percent), and slices for plotting.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "abbe/identify/workspace_map.hpp"
#include "abbe/io/atomic_file.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/machine/machine.hpp"
#include "box_option.hpp"
#include "command.hpp"
#include "interpreter_options.hpp"
#include "output_options.hpp"
#include "progress.hpp"

namespace abbe::cli {
namespace {

struct MapCliOptions {
  std::string machine;
  double grid = 50.0;
  std::vector<double> box;
  std::string model = "all";
  std::string output;
  std::string slices;
  std::string json;
  double tool_length = -1.0;  // < 0: the machine's
};

int run_map(const MapCliOptions& o, const GlobalOptions& g) {
  const machine::Machine machine = machine::Machine::load(o.machine);
  identify::MapOptions mo;
  mo.models = model::parse_model_list(o.model);
  if (!(o.grid > 0.0)) bad_option("--grid", "grid spacing must be > 0 mm");
  mo.spacing_mm = o.grid;
  mo.tool_length = o.tool_length >= 0.0 ? o.tool_length : machine.tool_length();
  identify::travel_box(machine, mo.tool_length, mo.lo, mo.hi);
  if (!o.box.empty()) parse_box_option(o.box, mo.lo, mo.hi);
  double n = 1.0;
  for (int i = 0; i < 3; ++i) n *= std::floor((mo.hi[i] - mo.lo[i]) / mo.spacing_mm) + 2.0;
  if (n > 5e6) bad_option("--grid", "more than 5 million points; use a coarser grid");

  // Progress on a terminal: grid points evaluated (points × models).
  std::uint64_t evaluations = 1;
  for (int i = 0; i < 3; ++i)
    evaluations *= identify::grid_axis(mo.lo[i], mo.hi[i], mo.spacing_mm).size();
  Progress progress("map", evaluations * mo.models.size(), !g.quiet, "points");
  if (progress.active()) mo.progress = [&](std::size_t done) { progress.update(done); };
  const identify::WorkspaceMap map = identify::compute_map(machine, mo);
  progress.finish();
  if (!o.output.empty()) io::write_file_atomically(o.output, identify::map_to_csv(map));
  if (!o.slices.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.slices, ec);
    if (ec)
      throw InputError({o.slices, 0, 0, "--slices", ""},
                       "cannot create the directory: " + ec.message());
    // XY at the lowest, middle and highest z; XZ at the middle y; YZ at the middle x.
    const std::size_t nz = map.zs.size();
    std::vector<std::size_t> zi{0, nz / 2, nz - 1};
    zi.erase(std::unique(zi.begin(), zi.end()), zi.end());
    for (std::size_t k : zi)
      io::write_file_atomically(fmt::format("{}/xy_z{:g}.csv", o.slices, map.zs[k]),
                                identify::map_slice_csv(map, "xy", k));
    io::write_file_atomically(fmt::format("{}/xz_y{:g}.csv", o.slices, map.ys[map.ys.size() / 2]),
                              identify::map_slice_csv(map, "xz", map.ys.size() / 2));
    io::write_file_atomically(fmt::format("{}/yz_x{:g}.csv", o.slices, map.xs[map.xs.size() / 2]),
                              identify::map_slice_csv(map, "yz", map.xs.size() / 2));
  }

  std::string text = fmt::format(
      "{}: {} × {} × {} = {} grid points, box ({:g}, {:g}, {:g}) – ({:g}, {:g}, {:g}) mm, "
      "tool length {:g} mm\n",
      machine.name(), map.xs.size(), map.ys.size(), map.zs.size(), map.points.size(), mo.lo.x(),
      mo.lo.y(), mo.lo.z(), mo.hi.x(), mo.hi.y(), mo.hi.z(), mo.tool_length);
  text += fmt::format("  {:<7} {:>10} {:>10} {:>10}  (|d|, µm)\n", "model", "mean", "rms", "max");
  nlohmann::json js = {{"machine", machine.name()},
                       {"points", map.points.size()},
                       {"spacing_mm", mo.spacing_mm},
                       {"tool_length_mm", mo.tool_length},
                       {"box", {mo.lo.x(), mo.lo.y(), mo.lo.z(), mo.hi.x(), mo.hi.y(), mo.hi.z()}},
                       {"out_of_range_lookups", map.out_of_range_lookups}};
  js["models"] = nlohmann::json::array();
  for (const auto& s : map.stats) {
    text += fmt::format("  {:<7} {:>10.4f} {:>10.4f} {:>10.4f}", model::to_string(s.model),
                        s.mean_um, s.rms_um, s.max_um);
    nlohmann::json m = {{"model", model::to_string(s.model)},
                        {"mean_um", s.mean_um},
                        {"rms_um", s.rms_um},
                        {"max_um", s.max_um}};
    if (model::descriptor(s.model).second_order) {
      text += fmt::format("   second order: max {:.5f}, rms {:.5f}", s.second_order_max_um,
                          s.second_order_rms_um);
      m["second_order_max_um"] = s.second_order_max_um;
      m["second_order_rms_um"] = s.second_order_rms_um;
    }
    text += '\n';
    js["models"].push_back(m);
  }
  if (map.has_comparison) {
    text += fmt::format(
        "  htm vs ae-arm: mean |d| {:.4f} µm larger with htm; ae-arm mean {:.1f} % smaller; "
        "mean |d_htm − d_ae-arm| {:.4f} µm\n",
        map.mean_difference_um, map.percent_smaller, map.mean_abs_vector_difference_um);
    js["htm_vs_ae_arm"] = {{"mean_difference_um", map.mean_difference_um},
                           {"percent_smaller", map.percent_smaller},
                           {"mean_abs_vector_difference_um", map.mean_abs_vector_difference_um}};
  }
  if (map.out_of_range_lookups > 0)
    text += fmt::format("  {} lookups outside the measured range ({})\n", map.out_of_range_lookups,
                        machine::to_string(machine.out_of_range()));
  if (!o.json.empty()) io::write_file_atomically(o.json, js.dump(2) + "\n");
  std::fputs(text.c_str(), summary_stream(o.output == "-" ? o.output : o.json));
  return kOk;
}

const CommandRegistrar registrar(
    "map", "Volumetric error over the travel (or a box) per model, htm vs ae-arm", 60,
    [](CLI::App& sub, const GlobalOptions& g) -> CommandAction {
      auto o = std::make_shared<MapCliOptions>();
      sub.footer(
          "Example: abbe map --machine machines/sample/machine.yaml --grid 100 --json map.json");
      sub.add_option("--machine", o->machine, "Machine file (YAML, docs/formats.md)")->required();
      sub.add_option("--grid", o->grid, "Grid spacing, mm")->capture_default_str();
      sub.add_option("--box", o->box, std::string(kBoxHelp) + " (default: the travel)")
          ->delimiter(',')
          ->expected(6);
      sub.add_option("--model", o->model, model::model_names_text(true))
          ->check(CLI::IsMember(model::model_names(true)))
          ->capture_default_str();
      sub.add_option("--tool-length", o->tool_length, "Tool length, mm (default: the machine's)");
      add_output_option(sub, o->output, "CSV of the grid points");
      sub.add_option("--slices", o->slices, "Directory for slice CSVs (XY at 3 z, XZ, YZ)");
      sub.add_option("--json", o->json, "Statistics as JSON to FILE (- for stdout)");
      const GlobalOptions* gp = &g;
      return [o, gp] { return run_map(*o, *gp); };
    });

}  // namespace
}  // namespace abbe::cli
