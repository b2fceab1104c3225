// sim::apply_real_conventions (docs/virtual-machine.md §5a): the rewritten
// campaign has positioning and angles zero at the first target, straightness
// with zero mean and zero least-squares slope, runs shifted like the table,
// reflector errors only where asked, and the squareness change of the rule in
// docs/models.md (an EYX slope κ µm/mm removed changes EC0Y by −1000·κ µrad).
#include "abbe/sim/real_conventions.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "abbe/sim/laser_campaign.hpp"

namespace abbe {
namespace {

sim::GeneratedMachine machine() {
  sim::GeneratorOptions o;
  o.seed = 7;
  o.spacing_mm = 50.0;
  o.runs = 2;
  return sim::generate_machine(o);
}

TEST(RealConventions, TablesAreZeroedAndLeveled) {
  sim::GeneratedMachine g = machine();
  sim::CampaignResult r = sim::run_campaign(g);
  const sim::CampaignResult before = r;
  const sim::GeneratedMachine g0 = g;
  const sim::ConventionRecord rec = sim::apply_real_conventions(g, r, {});
  for (int j = 0; j < 3; ++j)
    for (int c = 0; c < 6; ++c) {
      double n = 0, ss = 0, sv = 0, sss = 0, ssv = 0, first = NAN;
      for (const sim::TableEntry& e : r.table) {
        if (e.axis != j || e.component != c) continue;
        const double v = 0.5 * (e.fwd + e.rev);
        if (std::isnan(first)) first = v;
        n += 1;
        ss += e.position_mm;
        sv += v;
        sss += e.position_mm * e.position_mm;
        ssv += e.position_mm * v;
      }
      ASSERT_GT(n, 2) << j << c;
      if (c == j || c >= 3) {
        EXPECT_NEAR(first, 0.0, 1e-9) << j << c;
      } else {
        EXPECT_NEAR(sv / n, 0.0, 1e-9) << j << c;                                      // mean
        EXPECT_NEAR((ssv - ss * sv / n) / (sss - ss * ss / n), 0.0, 1e-12) << j << c;  // slope
      }
    }
  // Runs moved by the same a + b·s as the table.
  for (std::size_t i = 0; i < r.runs.size(); ++i) {
    const sim::RunReading& a = before.runs[i];
    const sim::RunReading& b = r.runs[i];
    EXPECT_NEAR(a.deviation - b.deviation,
                rec.a[a.axis][a.component] + rec.b[a.axis][a.component] * a.target_mm, 1e-9);
  }
  // Squareness: EC0Y takes the removed EYX and EXY slopes (+1000·(−b)·… see the
  // rule), EB0Z the EZX, EXZ ones, EA0Z the EZY, EYZ ones and the EAY, EBY constants.
  EXPECT_NEAR(rec.squareness_change.ec0y, -1000.0 * (rec.b[0][1] + rec.b[1][0]), 1e-9);
  EXPECT_NEAR(rec.squareness_change.eb0z, 1000.0 * (rec.b[0][2] + rec.b[2][0]) + rec.a[1][4], 1e-9);
  EXPECT_NEAR(rec.squareness_change.ea0z, -1000.0 * (rec.b[1][2] + rec.b[2][1]) + rec.a[1][3],
              1e-9);
  EXPECT_NEAR(r.squareness.ec0y - before.squareness.ec0y, rec.squareness_change.ec0y, 1e-12);
  // No reflector error asked: the recorded points are the true ones.
  for (int j = 0; j < 3; ++j)
    EXPECT_EQ(g.campaign.axes[static_cast<std::size_t>(j)].point,
              g0.campaign.axes[static_cast<std::size_t>(j)].point);
}

TEST(RealConventions, ReflectorErrorsOfTheAskedSize) {
  sim::GeneratedMachine g = machine();
  const sim::GeneratedMachine g0 = g;
  sim::CampaignResult r = sim::run_campaign(g);
  sim::RealConventions rc;
  rc.reflector_sigma_mm = 3.0;
  rc.seed = 5;
  sim::apply_real_conventions(g, r, rc);
  double sum2 = 0;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d d = g.campaign.axes[static_cast<std::size_t>(j)].point -
                              g0.campaign.axes[static_cast<std::size_t>(j)].point;
    EXPECT_GT(d.norm(), 0.0);
    EXPECT_LT(d.cwiseAbs().maxCoeff(), 5.0 * 3.0);
    sum2 += d.squaredNorm();
  }
  EXPECT_GT(std::sqrt(sum2 / 9.0), 0.5);  // 9 draws of N(0, 3 mm)
  EXPECT_LT(std::sqrt(sum2 / 9.0), 6.0);
}

}  // namespace
}  // namespace abbe
