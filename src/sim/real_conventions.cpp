#include "abbe/sim/real_conventions.hpp"

#include <Eigen/Core>

#include "abbe/sim/random.hpp"

namespace abbe::sim {

ConventionRecord apply_real_conventions(GeneratedMachine& machine, CampaignResult& result,
                                        const RealConventions& conventions) {
  ConventionRecord rec;
  // H: the linear part of the change of the prediction, µm/m (= µrad):
  // e_new − e_old = H·P + constant.
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (int j = 0; j < 3; ++j) {
    // I − D_U: the coordinates the arm of axis j changes with (the axes that
    // do not carry its reflector).
    Eigen::Matrix3d free = Eigen::Matrix3d::Identity();
    for (int i = 0; i < 3; ++i)
      if (machine.truth.chain.moves(j, i)) free(i, i) = 0.0;
    for (int c = 0; c < 6; ++c) {
      double n = 0, ss = 0, sv = 0, sss = 0, ssv = 0, v_ref = 0;
      bool first = true;
      for (const TableEntry& e : result.table) {
        if (e.axis != j || e.component != c) continue;
        const double v = 0.5 * (e.fwd + e.rev);
        if (first) v_ref = v;
        first = false;
        n += 1;
        ss += e.position_mm;
        sv += v;
        sss += e.position_mm * e.position_mm;
        ssv += e.position_mm * v;
      }
      if (n == 0) continue;
      double a = 0, b = 0;
      if (c == j && conventions.zero_positioning) {
        a = v_ref;
      } else if (c < 3 && c != j && conventions.remove_straightness_slope) {
        const double var = sss - ss * ss / n;
        b = var > 0 ? (ssv - ss * sv / n) / var : 0.0;
        a = (sv - b * ss) / n;
        h(c, j) -= 1000.0 * b;  // e_c changes by −b·s_j (µm/mm → µm/m)
      } else if (c >= 3 && conventions.relative_angles) {
        a = v_ref;
        Eigen::Vector3d d = Eigen::Vector3d::Zero();
        d[c - 3] = -a;  // µrad
        Eigen::Matrix3d cross;
        cross << 0, -d.z(), d.y(), d.z(), 0, -d.x(), -d.y(), d.x(), 0;
        h += cross * free;  // Δε × (arm), the arm's linear part
      }
      rec.a[j][c] = a;
      rec.b[j][c] = b;
      if (a == 0.0 && b == 0.0) continue;
      for (TableEntry& e : result.table)
        if (e.axis == j && e.component == c) {
          e.fwd -= a + b * e.position_mm;
          e.rev -= a + b * e.position_mm;
        }
      for (RunReading& r : result.runs)
        if (r.axis == j && r.component == c) r.deviation -= a + b * r.target_mm;
    }
  }
  // H = W (a rotation) − S (the squareness terms (−EC0Y·y + EB0Z·z, −EA0Z·z, 0)):
  // the lower triangle fixes W, the upper one the squareness change.
  rec.squareness_change.ec0y = h(1, 0) + h(0, 1);
  rec.squareness_change.eb0z = -(h(2, 0) + h(0, 2));
  rec.squareness_change.ea0z = h(2, 1) + h(1, 2);
  result.squareness.ec0y += rec.squareness_change.ec0y;
  result.squareness.eb0z += rec.squareness_change.eb0z;
  result.squareness.ea0z += rec.squareness_change.ea0z;

  if (conventions.reflector_sigma_mm > 0.0) {
    Random rng(conventions.seed);
    for (AxisRecord& a : machine.campaign.axes)
      for (int i = 0; i < 3; ++i) a.point[i] += conventions.reflector_sigma_mm * rng.normal();
  }
  return rec;
}

}  // namespace abbe::sim
