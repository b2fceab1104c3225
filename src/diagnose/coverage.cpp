#include "coverage.hpp"

#include <algorithm>
#include <cmath>

namespace abbe::diagnose {

void Coverage::Range::add(double x) {
  lo = std::min(lo, x);
  hi = std::max(hi, x);
}

Coverage::Coverage(const Problem& pb) {
  auto sign_bit = [](int v) { return v < 0 ? 1u : 2u; };
  for (const PointContext& pc : pb.points) {
    for (std::size_t v = 0; v < 3; ++v) {
      all_[v].add(pc.s[static_cast<Eigen::Index>(v)]);
      tip_[v].add(pc.p[static_cast<Eigen::Index>(v)]);
      if (pc.dir[v] != 0) signs_[v] |= sign_bit(pc.dir[v]);
    }
    all_[3].add(pc.t);
  }
  for (const Observation& ob : pb.obs) {
    const PointContext& pc = pb.points[ob.point];
    for (std::size_t i = 0; i < 3; ++i) {
      if (std::abs(ob.u[static_cast<Eigen::Index>(i)]) <= 1e-9) continue;
      for (std::size_t v = 0; v < 3; ++v) in_[i][v].add(pc.s[static_cast<Eigen::Index>(v)]);
      in_[i][3].add(pc.t);
      for (std::size_t j = 0; j < 3; ++j)
        if (pc.dir[j] != 0) signs_in_[i][j] |= sign_bit(pc.dir[j]);
    }
  }
}

}  // namespace abbe::diagnose
