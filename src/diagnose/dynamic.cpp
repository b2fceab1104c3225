#include "abbe/diagnose/dynamic.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <map>

#include "abbe/diagnose/statistics.hpp"

namespace abbe::diagnose {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kSpikeWindowRad = 10.0 * kPi / 180.0;  // after a quadrant point

struct Reading {
  Eigen::Index obs;
  double theta;  // angle in the plane, from the first axis towards the second
  int travel;    // +1 the angle grows (CCW), −1 (CW)
};

}  // namespace

CircleCheck check_circles(const Problem& pb, const Eigen::VectorXd& r, double sigma) {
  CircleCheck out;
  if (!(sigma > 0.0)) return out;
  // The observations of each set; a set is a circle when every u is a radial
  // direction in one coordinate plane (dn of a ballbar).
  std::map<std::string, std::vector<std::size_t>> by_set;
  for (std::size_t o = 0; o < pb.obs.size(); ++o)
    by_set[pb.points[pb.obs[o].point].set].push_back(o);
  const double alpha = 0.01 / static_cast<double>(std::max<std::size_t>(by_set.size(), 1));
  for (const std::string& set : pb.sets) {
    const auto& obs = by_set[set];
    if (obs.size() < 36) continue;
    int normal = -1;
    for (int k = 0; k < 3 && normal < 0; ++k) {
      bool flat = true;
      for (std::size_t o : obs) flat = flat && std::abs(pb.obs[o].u[k]) < 1e-9;
      if (flat) normal = k;
    }
    if (normal < 0) continue;
    const int a = normal == 0 ? 1 : 0, b = normal == 2 ? 1 : 2;
    bool radial = true, unit = true;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (std::size_t o : obs) c += pb.points[pb.obs[o].point].p;
    c /= static_cast<double>(obs.size());
    std::vector<Reading> rd;
    int ways = 0;
    for (std::size_t o : obs) {
      const Eigen::Vector3d& u = pb.obs[o].u;
      const Eigen::Vector3d q = pb.points[pb.obs[o].point].p - c;
      unit = unit && std::abs(u.norm() - 1.0) < 1e-6;
      // u along q, outwards (a radius of the circle about the set's centre).
      const double qn = std::hypot(q[a], q[b]);
      radial = radial && qn > 1e-6 && std::abs(q[a] * u[b] - q[b] * u[a]) < 1e-3 * qn &&
               q[a] * u[a] + q[b] * u[b] > 0.5 * qn;
      const double th = std::atan2(u[b], u[a]);
      const auto& d = pb.points[pb.obs[o].point].dir;
      const double s = -std::sin(th) * d[static_cast<std::size_t>(a)] +
                       std::cos(th) * d[static_cast<std::size_t>(b)];
      const int travel = s > 1e-9 ? 1 : s < -1e-9 ? -1 : 0;
      if (travel == 0) continue;
      ways |= travel > 0 ? 1 : 2;
      rd.push_back({static_cast<Eigen::Index>(o), th, travel});
    }
    if (!radial || !unit) continue;
    out.circles.push_back(set);
    if (ways != 3 || rd.size() < 36) continue;  // one way only: a static ellipse looks the same

    // Servo mismatch: r ≈ travel·(β1 sin 2θ + β2 cos 2θ).
    Eigen::MatrixXd G(static_cast<Eigen::Index>(rd.size()), 2);
    Eigen::VectorXd y(static_cast<Eigen::Index>(rd.size()));
    for (std::size_t i = 0; i < rd.size(); ++i) {
      const auto row = static_cast<Eigen::Index>(i);
      G(row, 0) = rd[i].travel * std::sin(2.0 * rd[i].theta);
      G(row, 1) = rd[i].travel * std::cos(2.0 * rd[i].theta);
      y[row] = r[rd[i].obs];
    }
    const Eigen::Matrix2d GtG = G.transpose() * G;
    const Eigen::Vector2d b2 = G.transpose() * y;
    const Eigen::Vector2d beta = GtG.ldlt().solve(b2);
    const double drop = b2.dot(beta);
    const double amp = beta.norm();
    if (drop > sigma * sigma * chi2_upper_quantile(2, alpha) && amp > 0.3 * sigma)
      out.findings.push_back({"servo_mismatch", set, amp, std::sqrt(drop) / sigma});

    // Reversal spikes: the readings just after a quadrant point (an axis
    // reverses) against the rest.
    double in_sum = 0.0, out_sum = 0.0;
    int in_n = 0, out_n = 0;
    for (const Reading& x : rd) {
      // Angle travelled since the last quadrant point.
      const double along = x.travel > 0 ? x.theta : -x.theta;
      double since = std::fmod(along, 0.5 * kPi);
      if (since < 0.0) since += 0.5 * kPi;
      const double v = r[x.obs];
      if (since > 1e-9 && since <= kSpikeWindowRad) {
        in_sum += v;
        ++in_n;
      } else {
        out_sum += v;
        ++out_n;
      }
    }
    if (in_n >= 4 && out_n >= 4) {
      const double h = in_sum / in_n - out_sum / out_n;
      const double se = sigma * std::sqrt(1.0 / in_n + 1.0 / out_n);
      if (std::abs(h) > normal_upper_quantile(alpha / 2.0) * se && std::abs(h) > 0.5 * sigma)
        out.findings.push_back({"reversal_spikes", set, h, std::abs(h) / se});
    }
  }
  return out;
}

}  // namespace abbe::diagnose
