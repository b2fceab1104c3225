#pragma once
// What every hand-made diagnosis Problem of the selection tests needs once
// its points and observations are in: the observed values, its one set, the
// measured directions and the travel box the candidates are normalised to.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/residuals.hpp"

namespace abbe::diagnose::test {

inline void finish_problem(Problem& pb, const std::vector<double>& y, const std::string& set,
                           const std::array<bool, 3>& directions, const Eigen::Vector3d& lo,
                           const Eigen::Vector3d& hi) {
  pb.y = Eigen::Map<const Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size()));
  pb.sets = {set};
  pb.direction_present = directions;
  for (int v = 0; v < 3; ++v) {
    pb.var_lo[static_cast<std::size_t>(v)] = lo[v];
    pb.var_hi[static_cast<std::size_t>(v)] = hi[v];
  }
  pb.travel_mid = 0.5 * (lo + hi);
  pb.travel_half = (0.5 * (hi - lo)).cwiseMax(1e-9);
}

// One point read along one direction u (a laser line, a probe): the point,
// its observation, the observed value and its file line.
inline void add_reading(Problem& pb, std::vector<double>& y, const PointContext& pc,
                        const Eigen::Vector3d& u, double value) {
  pb.obs.push_back({static_cast<std::uint32_t>(pb.points.size()), u});
  y.push_back(value);
  pb.points.push_back(pc);
  pb.lines.push_back(pb.points.size() + 1);
}

// A term of `kind` on `axis`, acting in `direction` (-1: none).
inline Term make_term(TermKind kind, int axis, int direction) {
  Term t;
  t.kind = kind;
  t.axis = axis;
  t.direction = direction;
  return t;
}

// The problem's datum and one fixed candidate of `kind` (axis, direction).
inline CandidateSet datum_and(const Problem& pb, TermKind kind, int axis, int direction) {
  CandidateSet cs;
  cs.datum = build_candidates(pb, CandidateOptions{}).datum;
  cs.fixed = {make_term(kind, axis, direction)};
  return cs;
}

}  // namespace abbe::diagnose::test
