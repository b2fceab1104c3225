#include "abbe/identify/workspace_map.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "abbe/model/error_model.hpp"

namespace abbe::identify {

void travel_box(const machine::Machine& machine, double tool_length, Eigen::Vector3d& lo,
                Eigen::Vector3d& hi) {
  for (machine::Axis a : machine::kAxes) {
    const int i = machine::index(a);
    lo[i] = machine.travel(a).min;
    hi[i] = machine.travel(a).max;
  }
  lo.z() -= tool_length;
  hi.z() -= tool_length;
}

std::vector<double> grid_axis(double lo, double hi, double spacing_mm) {
  if (!(hi > lo)) return {lo};
  const auto n = static_cast<std::size_t>(std::ceil((hi - lo) / spacing_mm - 1e-9));
  std::vector<double> v(n + 1);
  for (std::size_t i = 0; i <= n; ++i)
    v[i] = i == n ? hi : lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(n);
  return v;
}

WorkspaceMap compute_map(const machine::Machine& machine, const MapOptions& options) {
  WorkspaceMap map;
  map.xs = grid_axis(options.lo.x(), options.hi.x(), options.spacing_mm);
  map.ys = grid_axis(options.lo.y(), options.hi.y(), options.spacing_mm);
  map.zs = grid_axis(options.lo.z(), options.hi.z(), options.spacing_mm);
  for (double z : map.zs)
    for (double y : map.ys)
      for (double x : map.xs) map.points.emplace_back(x, y, z);
  map.models = options.models;
  const auto n = static_cast<double>(map.points.size());
  for (model::ModelKind kind : options.models) {
    const model::ErrorModel em(machine, kind);
    model::ModelData data;
    std::vector<Eigen::Vector3d> dev;
    dev.reserve(map.points.size());
    ModelMapStats st;
    st.model = kind;
    double sum = 0.0, sum2 = 0.0, so2 = 0.0;
    for (const Eigen::Vector3d& p : map.points) {
      model::EvalPoint ep;
      ep.p = p;
      ep.tool_length = options.tool_length;
      const model::Deviation d = em.evaluate(ep, data);
      dev.push_back(d.e_um);
      const double m = d.e_um.norm();
      sum += m;
      sum2 += m * m;
      st.max_um = std::max(st.max_um, m);
      st.max_abs_component_um = st.max_abs_component_um.cwiseMax(d.e_um.cwiseAbs());
      st.second_order_max_um = std::max(st.second_order_max_um, d.second_order_um.norm());
      so2 += d.second_order_um.squaredNorm();
      if (options.progress && ((dev.size() & 4095) == 0 || dev.size() == map.points.size()))
        options.progress(map.deviation_um.size() * map.points.size() + dev.size());
    }
    st.mean_um = sum / n;
    st.rms_um = std::sqrt(sum2 / n);
    st.second_order_rms_um = std::sqrt(so2 / n);
    map.out_of_range_lookups += data.out_of_range_lookups;
    map.deviation_um.push_back(std::move(dev));
    map.stats.push_back(st);
  }
  int ih = -1, ia = -1;
  for (std::size_t i = 0; i < map.models.size(); ++i) {
    if (map.models[i] == model::ModelKind::htm) ih = static_cast<int>(i);
    if (map.models[i] == model::ModelKind::ae_arm) ia = static_cast<int>(i);
  }
  if (ih >= 0 && ia >= 0) {
    const ModelMapStats& h = map.stats[static_cast<std::size_t>(ih)];
    const ModelMapStats& a = map.stats[static_cast<std::size_t>(ia)];
    map.has_comparison = true;
    map.mean_difference_um = h.mean_um - a.mean_um;
    map.percent_smaller = h.mean_um > 0.0 ? 100.0 * (h.mean_um - a.mean_um) / h.mean_um : 0.0;
    double s = 0.0;
    for (std::size_t p = 0; p < map.points.size(); ++p)
      s += (map.deviation_um[static_cast<std::size_t>(ih)][p] -
            map.deviation_um[static_cast<std::size_t>(ia)][p])
               .norm();
    map.mean_abs_vector_difference_um = s / n;
  }
  return map;
}

namespace {
void append_header(std::string& out, const WorkspaceMap& map) {
  for (model::ModelKind k : map.models) {
    const char* m = model::to_string(k);
    out += fmt::format(",{0}_dx,{0}_dy,{0}_dz,{0}_d", m);
  }
  out += '\n';
}
void append_values(std::string& out, const WorkspaceMap& map, std::size_t p) {
  for (std::size_t m = 0; m < map.models.size(); ++m) {
    const Eigen::Vector3d& d = map.deviation_um[m][p];
    out += fmt::format(",{:.6g},{:.6g},{:.6g},{:.6g}", d.x(), d.y(), d.z(), d.norm());
  }
  out += '\n';
}
}  // namespace

std::string map_to_csv(const WorkspaceMap& map) {
  std::string out = "x,y,z";
  append_header(out, map);
  for (std::size_t p = 0; p < map.points.size(); ++p) {
    const Eigen::Vector3d& q = map.points[p];
    out += fmt::format("{:.6g},{:.6g},{:.6g}", q.x(), q.y(), q.z());
    append_values(out, map, p);
  }
  return out;
}

std::string map_slice_csv(const WorkspaceMap& map, const std::string& plane, std::size_t index) {
  const std::size_t nx = map.xs.size(), ny = map.ys.size(), nz = map.zs.size();
  auto at = [&](std::size_t i, std::size_t j, std::size_t k) { return (k * ny + j) * nx + i; };
  std::string out;
  if (plane == "xy") {
    if (index >= nz) throw std::out_of_range("slice index");
    out = "x,y,z";
    append_header(out, map);
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        out += fmt::format("{:.6g},{:.6g},{:.6g}", map.xs[i], map.ys[j], map.zs[index]);
        append_values(out, map, at(i, j, index));
      }
  } else if (plane == "xz") {
    if (index >= ny) throw std::out_of_range("slice index");
    out = "x,z,y";
    append_header(out, map);
    for (std::size_t k = 0; k < nz; ++k)
      for (std::size_t i = 0; i < nx; ++i) {
        out += fmt::format("{:.6g},{:.6g},{:.6g}", map.xs[i], map.zs[k], map.ys[index]);
        append_values(out, map, at(i, index, k));
      }
  } else if (plane == "yz") {
    if (index >= nx) throw std::out_of_range("slice index");
    out = "y,z,x";
    append_header(out, map);
    for (std::size_t k = 0; k < nz; ++k)
      for (std::size_t j = 0; j < ny; ++j) {
        out += fmt::format("{:.6g},{:.6g},{:.6g}", map.ys[j], map.zs[k], map.xs[index]);
        append_values(out, map, at(index, j, k));
      }
  } else {
    throw std::invalid_argument("plane must be xy, xz or yz");
  }
  return out;
}

}  // namespace abbe::identify
