#include "abbe/diagnose/noise.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <vector>

namespace abbe::diagnose {
namespace {

// σ of one observation from differences of two: 1.4826·median|Δ| / √2.
double robust_sigma(std::vector<double>& diffs) {
  if (diffs.empty()) return 0.0;
  for (double& d : diffs) d = std::abs(d);
  const auto mid = diffs.begin() + static_cast<std::ptrdiff_t>(diffs.size() / 2);
  std::nth_element(diffs.begin(), mid, diffs.end());
  return 1.482602218505602 * *mid / std::sqrt(2.0);
}

}  // namespace

NoiseEstimate estimate_noise(const Problem& pb) {
  NoiseEstimate est;
  est.method = "none";
  // Repeated points: key = set, position (µm grid), approach directions, u.
  using Key = std::tuple<std::string, long long, long long, long long, int, int, int, long long,
                         long long, long long>;
  std::map<Key, double> first;
  std::vector<double> rep;
  auto q = [](double v, double unit) { return static_cast<long long>(std::llround(v / unit)); };
  for (std::size_t o = 0; o < pb.obs.size(); ++o) {
    const Observation& ob = pb.obs[o];
    const PointContext& pc = pb.points[ob.point];
    const Key k{
        pc.set,    q(pc.p.x(), 1e-3), q(pc.p.y(), 1e-3), q(pc.p.z(), 1e-3), pc.dir[0],
        pc.dir[1], pc.dir[2],         q(ob.u.x(), 1e-6), q(ob.u.y(), 1e-6), q(ob.u.z(), 1e-6)};
    const double y = pb.y[static_cast<Eigen::Index>(o)];
    const auto it = first.find(k);
    if (it == first.end()) {
      first.emplace(k, y);
    } else {
      rep.push_back(y - it->second);
    }
  }
  if (rep.size() >= 10) {
    est.pairs = rep.size();
    est.sigma_um = robust_sigma(rep);
    est.method = "repeated points";
    return est;
  }
  // Neighbours in measurement order: second differences of consecutive
  // observations of the same set along the same direction (a trend along
  // the run — a scale, a drift — cancels).
  std::map<std::tuple<std::string, long long, long long, long long>, std::pair<double, int>> prev;
  std::map<std::tuple<std::string, long long, long long, long long>, double> prev2;
  std::vector<double> nb;
  for (std::size_t o = 0; o < pb.obs.size(); ++o) {
    const Observation& ob = pb.obs[o];
    const PointContext& pc = pb.points[ob.point];
    const auto k = std::make_tuple(pc.set, q(ob.u.x(), 1e-6), q(ob.u.y(), 1e-6), q(ob.u.z(), 1e-6));
    const double y = pb.y[static_cast<Eigen::Index>(o)];
    auto& [p1, seen] = prev[k];
    if (seen >= 2) nb.push_back((y - 2.0 * p1 + prev2[k]) * std::sqrt(2.0 / 6.0));
    prev2[k] = p1;
    p1 = y;
    seen = std::min(seen + 1, 2);
  }
  if (nb.size() >= 10) {
    est.pairs = nb.size();
    est.sigma_um = robust_sigma(nb);
    est.method = "neighbour differences";
  }
  return est;
}

}  // namespace abbe::diagnose
