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

// Three consecutive points are a run when their two steps differ by at
// most this share of the longer one (equal spacing on a line).
constexpr double kRunTolerance = 0.2;

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
  // the run — a scale, a drift, a set-up rotation — cancels). Only where
  // the three points are equally spaced on a line: between points taken in
  // no spatial order (the holes of a plate in drilling order) a second
  // difference holds the whole structure, not the noise.
  struct Last {
    double y1 = 0.0, y2 = 0.0;
    Eigen::Vector3d p1, p2;
    int seen = 0;
  };
  std::map<std::tuple<std::string, long long, long long, long long>, Last> prev;
  std::vector<double> nb;
  for (std::size_t o = 0; o < pb.obs.size(); ++o) {
    const Observation& ob = pb.obs[o];
    const PointContext& pc = pb.points[ob.point];
    const auto k = std::make_tuple(pc.set, q(ob.u.x(), 1e-6), q(ob.u.y(), 1e-6), q(ob.u.z(), 1e-6));
    const double y = pb.y[static_cast<Eigen::Index>(o)];
    Last& l = prev[k];
    if (l.seen >= 2) {
      const Eigen::Vector3d a = l.p1 - l.p2, b = pc.p - l.p1;
      if ((b - a).norm() <= kRunTolerance * std::max(a.norm(), b.norm()))
        nb.push_back((y - 2.0 * l.y1 + l.y2) * std::sqrt(2.0 / 6.0));
    }
    l.y2 = l.y1;
    l.p2 = l.p1;
    l.y1 = y;
    l.p1 = pc.p;
    l.seen = std::min(l.seen + 1, 2);
  }
  if (nb.size() >= 10) {
    est.pairs = nb.size();
    est.sigma_um = robust_sigma(nb);
    est.method = "neighbour differences";
  }
  return est;
}

}  // namespace abbe::diagnose
