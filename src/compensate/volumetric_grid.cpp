// The volumetric grid (`abbe export grid`, docs/export.md): the predicted
// deviation of every model at the nodes of a regular grid over the travel,
// and the trilinear interpolation a volumetric compensation applies.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "abbe/compensate/controller_tables.hpp"
#include "abbe/io/atomic_file.hpp"
#include "abbe/io/fixed6.hpp"
#include "abbe/io/input_error.hpp"
#include "abbe/pipeline/model_set.hpp"

namespace abbe::compensate {
namespace {

const char* const kStepOption[3] = {"--step (X)", "--step (Y)", "--step (Z)"};
const char* const kCountOption[3] = {"--count (X)", "--count (Y)", "--count (Z)"};

// Cell index and fraction of p along one axis' nodes (clamped to the grid).
void locate(const std::vector<double>& n, double p, std::size_t& i, double& t) {
  if (n.size() < 2) {
    i = 0;
    t = 0.0;
    return;
  }
  const double h = (n.back() - n.front()) / static_cast<double>(n.size() - 1);
  double u = (p - n.front()) / h;
  u = std::min(std::max(u, 0.0), static_cast<double>(n.size() - 1));
  i = std::min(static_cast<std::size_t>(u), n.size() - 2);
  t = u - static_cast<double>(i);
}

// Writes the CSV in pieces of about 1 MB to `sink`.
void write_csv(const VolumetricGrid& grid,
               const std::function<void(const char*, std::size_t)>& sink) {
  fmt::memory_buffer b;
  const bool all = grid.models.size() > 1;
  std::string header = "x,y,z";
  for (model::ModelKind k : grid.models) {
    const std::string s = all ? "_" + model::descriptor(k).column_suffix : "";
    header += fmt::format(",dx{0},dy{0},dz{0}", s);
  }
  header += "\n";
  b.append(header.data(), header.data() + header.size());
  const std::size_t nx = grid.nodes[0].size(), ny = grid.nodes[1].size();
  for (std::size_t k = 0; k < grid.nodes[2].size(); ++k)
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        io::append_fixed6(b, grid.nodes[0][i]);
        b.push_back(',');
        io::append_fixed6(b, grid.nodes[1][j]);
        b.push_back(',');
        io::append_fixed6(b, grid.nodes[2][k]);
        const std::size_t idx = (k * ny + j) * nx + i;
        for (const auto& dev : grid.deviation_um)
          for (int c = 0; c < 3; ++c) {
            b.push_back(',');
            io::append_fixed6(b, dev[idx][c]);
          }
        b.push_back('\n');
        if (b.size() > (1u << 20)) {
          sink(b.data(), b.size());
          b.clear();
        }
      }
  sink(b.data(), b.size());
}

}  // namespace

Eigen::Vector3d VolumetricGrid::interpolate(std::size_t m, const Eigen::Vector3d& p) const {
  std::array<std::size_t, 3> i{};
  std::array<double, 3> t{};
  for (int a = 0; a < 3; ++a)
    locate(nodes[static_cast<std::size_t>(a)], p[a], i[static_cast<std::size_t>(a)],
           t[static_cast<std::size_t>(a)]);
  const std::size_t nx = nodes[0].size(), ny = nodes[1].size(), nz = nodes[2].size();
  const std::vector<Eigen::Vector3d>& d = deviation_um.at(m);
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  for (std::size_t dk = 0; dk < 2; ++dk) {
    const std::size_t k = std::min(i[2] + dk, nz - 1);
    const double wk = dk ? t[2] : 1.0 - t[2];
    for (std::size_t dj = 0; dj < 2; ++dj) {
      const std::size_t j = std::min(i[1] + dj, ny - 1);
      const double wj = dj ? t[1] : 1.0 - t[1];
      for (std::size_t di = 0; di < 2; ++di) {
        const std::size_t ii = std::min(i[0] + di, nx - 1);
        const double wi = di ? t[0] : 1.0 - t[0];
        const double w = wi * wj * wk;
        if (w != 0.0) out += w * d[(k * ny + j) * nx + ii];
      }
    }
  }
  return out;
}

VolumetricGrid volumetric_grid(const machine::Machine& machine, const GridOptions& options) {
  VolumetricGrid grid;
  grid.tool_length = options.tool_length;
  grid.models = options.models;
  for (machine::Axis a : machine::kAxes) {
    const auto j = static_cast<std::size_t>(machine::index(a));
    const machine::Travel& t = machine.travel(a);
    // Nodes over the axis positions s; the tool tip is s − L·e_z.
    const double shift = a == machine::Axis::z ? options.tool_length : 0.0;
    grid.nodes[j] = regular_positions(
        t.min - shift, t.max - shift, options.step[static_cast<Eigen::Index>(j)], options.count[j],
        kMaxGridNodes, options.count[j] ? kCountOption[j] : kStepOption[j]);
  }
  const double total = static_cast<double>(grid.nodes[0].size()) *
                       static_cast<double>(grid.nodes[1].size()) *
                       static_cast<double>(grid.nodes[2].size());
  if (total > static_cast<double>(kMaxGridNodes))
    throw InputError(
        {"<command line>", 0, 0, options.count[0] ? "--count" : "--step", ""},
        fmt::format("{} × {} × {} = {:.0f} grid nodes: at most {}", grid.nodes[0].size(),
                    grid.nodes[1].size(), grid.nodes[2].size(), total, kMaxGridNodes));
  pipeline::ModelSet models(machine, options.models, options.extension);
  grid.deviation_um.assign(options.models.size(), std::vector<Eigen::Vector3d>(grid.size()));
  const std::size_t nx = grid.nodes[0].size(), ny = grid.nodes[1].size();
  model::EvalPoint p;
  p.tool_length = options.tool_length;
  for (std::size_t k = 0; k < grid.nodes[2].size(); ++k)
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        p.p = Eigen::Vector3d(grid.nodes[0][i], grid.nodes[1][j], grid.nodes[2][k]);
        models.evaluate(p, machine.spec().file, 0);
        for (std::size_t m = 0; m < models.size(); ++m)
          grid.deviation_um[m][(k * ny + j) * nx + i] = models.deviations()[m].e_um;
      }
  return grid;
}

std::string grid_csv_text(const VolumetricGrid& grid) {
  std::string out;
  write_csv(grid, [&](const char* d, std::size_t n) { out.append(d, n); });
  return out;
}

std::string export_grid(const machine::Machine& machine, const GridOptions& options,
                        const std::string& path) {
  const VolumetricGrid grid = volumetric_grid(machine, options);
  io::AtomicOutputFile out(path);
  write_csv(grid, [&](const char* d, std::size_t n) { out.write(d, n); });
  out.commit();
  std::string s = fmt::format(
      "grid: {} × {} × {} = {} nodes over the travel, tool length {:.4f} mm, tool tip from "
      "X{:.4f} Y{:.4f} Z{:.4f} to X{:.4f} Y{:.4f} Z{:.4f} mm",
      grid.nodes[0].size(), grid.nodes[1].size(), grid.nodes[2].size(), grid.size(),
      grid.tool_length, grid.nodes[0].front(), grid.nodes[1].front(), grid.nodes[2].front(),
      grid.nodes[0].back(), grid.nodes[1].back(), grid.nodes[2].back());
  for (int a = 0; a < 3; ++a) {
    const auto& n = grid.nodes[static_cast<std::size_t>(a)];
    const double h =
        n.size() > 1 ? (n.back() - n.front()) / static_cast<double>(n.size() - 1) : 0.0;
    s += fmt::format("{}{} {:.4f}", a ? ", " : "; spacing ", "XYZ"[a], h);
  }
  s += " mm\n";
  for (std::size_t m = 0; m < grid.models.size(); ++m) {
    double max_d = 0.0;
    for (const auto& e : grid.deviation_um[m]) max_d = std::max(max_d, e.norm());
    s += fmt::format("{}: largest |d| at a node {:.3f} µm\n", model::to_string(grid.models[m]),
                     max_d);
  }
  s += fmt::format(
      "written to {} (columns x,y,z mm; dx,dy,dz µm, deviation P' − P: the "
      "correction is its negative)\n",
      path);
  return s;
}

}  // namespace abbe::compensate
