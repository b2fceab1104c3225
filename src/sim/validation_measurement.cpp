#include "abbe/sim/validation_measurement.hpp"

#include <fmt/format.h>

#include <cmath>

#include "abbe/sim/random.hpp"

namespace abbe::sim {

void default_box(const TruthMachine& truth, double tool_length, Eigen::Vector3d& lo,
                 Eigen::Vector3d& hi) {
  for (int j = 0; j < 3; ++j) {
    lo[j] = truth.axes[static_cast<std::size_t>(j)].travel_min;
    hi[j] = truth.axes[static_cast<std::size_t>(j)].travel_max;
  }
  lo.z() -= tool_length;  // P = s − L·e_z
  hi.z() -= tool_length;
}

namespace {
std::vector<double> levels(double lo, double hi, double spacing) {
  std::vector<double> v;
  const auto n = static_cast<long>(std::floor((hi - lo) / spacing + 1e-9));
  for (long k = 0; k <= n; ++k) v.push_back(lo + static_cast<double>(k) * spacing);
  if (hi - v.back() > 1e-6) v.push_back(hi);
  return v;
}
}  // namespace

std::vector<TipState> grid_points(const GridOptions& o) {
  const auto xs = levels(o.lo.x(), o.hi.x(), o.spacing_mm);
  const auto ys = levels(o.lo.y(), o.hi.y(), o.spacing_mm);
  const auto zs = levels(o.lo.z(), o.hi.z(), o.spacing_mm);
  std::vector<TipState> out;
  // The walk starts at machine zero (all axis positions 0) and snakes through
  // the grid: z levels from the top, y rows alternating, x alternating.
  Eigen::Vector3d prev(0.0, 0.0, -o.tool_length);
  std::array<int, 3> dir{0, 0, 0};
  double time = 0.0;
  bool x_up = true, y_up = true;
  for (int rep = 1; rep <= o.repeat; ++rep) {
    const std::string set = o.repeat > 1 && !o.one_setup ? o.set + std::to_string(rep) : o.set;
    for (std::size_t kz = zs.size(); kz-- > 0;) {
      for (std::size_t ky = 0; ky < ys.size(); ++ky) {
        const double y = ys[y_up ? ky : ys.size() - 1 - ky];
        for (std::size_t kx = 0; kx < xs.size(); ++kx) {
          const double x = xs[x_up ? kx : xs.size() - 1 - kx];
          const Eigen::Vector3d p(x, y, zs[kz]);
          for (int i = 0; i < 3; ++i) {
            if (p[i] > prev[i]) dir[static_cast<std::size_t>(i)] = 1;
            if (p[i] < prev[i]) dir[static_cast<std::size_t>(i)] = -1;
          }
          TipState tip;
          tip.p = p;
          tip.tool_length = o.tool_length;
          tip.dir = dir;
          tip.time = time;
          tip.set = set;
          out.push_back(tip);
          prev = p;
          time += o.interval_s;
        }
        x_up = !x_up;
      }
      y_up = !y_up;
    }
  }
  return out;
}

std::vector<MeasuredPoint> measure(const TruthMachine& truth, const std::vector<TipState>& tips,
                                   double noise_um, std::uint64_t seed) {
  Random rng(seed);
  std::vector<MeasuredPoint> out;
  out.reserve(tips.size());
  for (const TipState& tip : tips) {
    MeasuredPoint m;
    m.tip = tip;
    m.deviation_um = truth.deviation_um(tip);
    if (noise_um > 0.0)
      for (int i = 0; i < 3; ++i) m.deviation_um[i] += noise_um * rng.normal();
    out.push_back(m);
  }
  return out;
}

std::string measured_to_csv(const std::vector<MeasuredPoint>& points) {
  std::string out = "x,y,z,dx,dy,dz,t,vx,vy,vz,nx,ny,nz,dn,tool_length,set\n";
  for (const MeasuredPoint& m : points) {
    const TipState& t = m.tip;
    out +=
        fmt::format("{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.3f},{},{},{},,,,,{},{}\n",
                    t.p.x(), t.p.y(), t.p.z(), m.deviation_um.x(), m.deviation_um.y(),
                    m.deviation_um.z(), t.time, t.dir[0], t.dir[1], t.dir[2], t.tool_length, t.set);
  }
  return out;
}

io::MeasuredData to_measured_data(const std::vector<MeasuredPoint>& points,
                                  const std::string& file) {
  io::MeasuredData d;
  d.file = file;
  d.has_column = {true, true, true};
  std::size_t line = 2;
  for (const MeasuredPoint& m : points) {
    io::MeasuredRow r;
    r.p = m.tip.p;
    for (std::size_t k = 0; k < 3; ++k) r.d[k] = m.deviation_um[static_cast<Eigen::Index>(k)];
    r.t = m.tip.time;
    for (std::size_t k = 0; k < 3; ++k) r.v[k] = static_cast<std::int8_t>(m.tip.dir[k]);
    r.tool_length = m.tip.tool_length;
    r.set = m.tip.set;
    r.line = line++;
    d.rows.push_back(r);
  }
  return d;
}

}  // namespace abbe::sim
