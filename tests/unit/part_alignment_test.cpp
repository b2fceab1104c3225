// Part alignment (docs/models.md, "The part"): a best fit or a 3-2-1 datum
// alignment removes a rigid-body error exactly, does not see a rigid motion
// added to any error, and leaves each datum feature where the 3-2-1 rule puts it.
#include "abbe/pipeline/part_alignment.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "abbe/io/input_error.hpp"
#include "abbe/pipeline/aligned_prediction.hpp"

namespace abbe {
namespace {

using Eigen::Vector3d;
using pipeline::PartPoints;
using pipeline::RigidMotion;

RigidMotion motion(const Vector3d& rot_vec, const Vector3d& t_mm) {
  RigidMotion m;
  if (rot_vec.norm() > 0)
    m.rotation = Eigen::AngleAxisd(rot_vec.norm(), rot_vec.normalized()).toRotationMatrix();
  m.translation_mm = t_mm;
  return m;
}

// Points on the faces of a block (a part): top z = 0, side y = -40, end x = 0
// plus a pocket floor; as a CAM program would cut them.
struct Part {
  PartPoints pts;
  pipeline::DatumIndices datums;
};

Part block_part() {
  Part part;
  const Vector3d origin{-420.0, -180.0, -260.0};
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 6; ++j) {  // top face
      part.datums.primary.push_back(part.pts.size());
      part.pts.add(origin + Vector3d{12.0 * i, 8.0 * j, 0.0}, Vector3d::Zero());
    }
  for (int i = 0; i <= 10; ++i)
    for (int k = 1; k <= 3; ++k) {  // side face y = origin.y
      part.datums.secondary.push_back(part.pts.size());
      part.pts.add(origin + Vector3d{12.0 * i, 0.0, -6.0 * k}, Vector3d::Zero());
    }
  for (int j = 1; j <= 6; ++j)
    for (int k = 1; k <= 3; ++k) {  // end face x = origin.x
      part.datums.tertiary.push_back(part.pts.size());
      part.pts.add(origin + Vector3d{0.0, 8.0 * j, -6.0 * k}, Vector3d::Zero());
    }
  for (int i = 2; i <= 8; ++i)
    part.pts.add(origin + Vector3d{12.0 * i, 24.0, -9.0}, Vector3d::Zero());
  return part;
}

// Deviation (µm) of the points moved by `m`: (m(P) − P)·10³.
void set_rigid(PartPoints& pts, const RigidMotion& m) {
  for (std::size_t i = 0; i < pts.size(); ++i)
    pts.deviation_um[i] = 1e3 * (m.apply(pts.nominal_mm[i]) - pts.nominal_mm[i]);
}

// Adds the rigid motion `m` to the predicted points: P' ↦ m(P').
void add_rigid(PartPoints& pts, const RigidMotion& m) {
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vector3d p = pts.nominal_mm[i];
    const Vector3d pred = p + 1e-3 * pts.deviation_um[i];
    pts.deviation_um[i] = 1e3 * ((m.apply(pred) - pred)) + pts.deviation_um[i];
  }
}

void set_random(PartPoints& pts, unsigned seed, double amplitude_um) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, amplitude_um);
  for (auto& e : pts.deviation_um) e = {n(rng), n(rng), n(rng)};
}

double max_residual(const PartPoints& pts, const RigidMotion& m) {
  double r = 0;
  for (std::size_t i = 0; i < pts.size(); ++i)
    r = std::max(r,
                 pipeline::aligned_deviation_um(m, pts.nominal_mm[i], pts.deviation_um[i]).norm());
  return r;
}

const RigidMotion kSetups[] = {
    motion({0, 0, 0}, {0.012, -0.004, 0.020}),
    motion({20e-6, -35e-6, 50e-6}, {0.003, 0.011, -0.007}),
    motion({1e-3, 2e-3, -4e-3}, {1.5, -2.0, 0.5}),  // a setup far larger than any machine error
    motion({0.2, -0.1, 0.3}, {30.0, 10.0, -5.0}),   // and a rotation of tens of degrees
};

// The deviations left after each alignment agree point by point within tol_um.
void expect_same_residuals(const RigidMotion& fit_a, const pipeline::PartPoints& a,
                           const RigidMotion& fit_b, const pipeline::PartPoints& b, double tol_um) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Vector3d ra = pipeline::aligned_deviation_um(fit_a, a.nominal_mm[i], a.deviation_um[i]);
    const Vector3d rb = pipeline::aligned_deviation_um(fit_b, b.nominal_mm[i], b.deviation_um[i]);
    EXPECT_LT((rb - ra).norm(), tol_um) << i;
  }
}

TEST(PartAlignment, BestFitOfRigidOnlyErrorGivesZero) {
  Part part = block_part();
  for (const RigidMotion& setup : kSetups) {
    set_rigid(part.pts, setup);
    const RigidMotion fit = pipeline::best_fit(part.pts);
    EXPECT_LT(max_residual(part.pts, fit), 1e-7);  // µm
  }
}

TEST(PartAlignment, BestFitOfRigidOnlyErrorOnAPlanarPartGivesZero) {
  PartPoints pts;  // a 2.5-D contour: every point at one z
  for (int i = 0; i < 50; ++i) {
    const double a = 0.13 * i;
    pts.add({-300.0 + 80.0 * std::cos(a), -200.0 + 50.0 * std::sin(a), -250.0}, Vector3d::Zero());
  }
  for (const RigidMotion& setup : kSetups) {
    set_rigid(pts, setup);
    EXPECT_LT(max_residual(pts, pipeline::best_fit(pts)), 1e-7);
  }
}

TEST(PartAlignment, BestFitDoesNotSeeAnAddedRigidMotion) {
  Part part = block_part();
  set_random(part.pts, 7, 5.0);
  const PartPoints base = part.pts;
  const RigidMotion fit0 = pipeline::best_fit(base);
  for (const RigidMotion& setup : kSetups) {
    PartPoints moved = base;
    add_rigid(moved, setup);
    const RigidMotion fit = pipeline::best_fit(moved);
    expect_same_residuals(fit0, base, fit, moved, 1e-7);
  }
}

TEST(PartAlignment, BestFitIsTheLeastSquaresOptimum) {
  Part part = block_part();
  set_random(part.pts, 11, 3.0);
  const RigidMotion fit = pipeline::best_fit(part.pts);
  auto sum_sq = [&](const RigidMotion& m) {
    double s = 0;
    for (std::size_t i = 0; i < part.pts.size(); ++i)
      s += pipeline::aligned_deviation_um(m, part.pts.nominal_mm[i], part.pts.deviation_um[i])
               .squaredNorm();
    return s;
  };
  const double best = sum_sq(fit);
  // Mean residual zero (translation) and Σ q × r = 0 (rotation, q about the centroid).
  Vector3d c = Vector3d::Zero(), mean = Vector3d::Zero(), moment = Vector3d::Zero();
  for (const Vector3d& p : part.pts.nominal_mm) c += p;
  c /= static_cast<double>(part.pts.size());
  for (std::size_t i = 0; i < part.pts.size(); ++i) {
    const Vector3d r =
        pipeline::aligned_deviation_um(fit, part.pts.nominal_mm[i], part.pts.deviation_um[i]);
    mean += r;
    moment += (part.pts.nominal_mm[i] - c).cross(r);
  }
  EXPECT_LT(mean.norm() / static_cast<double>(part.pts.size()), 1e-9);
  EXPECT_LT(moment.norm() / static_cast<double>(part.pts.size()), 1e-6);  // mm·µm
  // Any nearby motion does worse.
  for (const RigidMotion& d : {motion({1e-6, 0, 0}, {0, 0, 0}), motion({0, 0, -1e-6}, {0, 0, 0}),
                               motion({0, 0, 0}, {1e-4, 0, 0}), motion({0, 0, 0}, {0, 0, -1e-4})})
    EXPECT_GT(sum_sq(d.after(fit)), best);
}

TEST(PartAlignment, BestFitRefusesTooFewOrCollinearPoints) {
  PartPoints pts;
  pts.add({0, 0, 0}, Vector3d::Zero());
  pts.add({10, 0, 0}, Vector3d::Zero());
  EXPECT_THROW(pipeline::best_fit(pts), pipeline::AlignmentError);
  pts.add({20, 0, 0}, {1, 2, 3});
  pts.add({30, 0, 0}, {1, 2, 3});
  EXPECT_THROW(pipeline::best_fit(pts), pipeline::AlignmentError);
}

TEST(PartAlignment, DatumsOfRigidOnlyErrorGiveZero) {
  Part part = block_part();
  for (const RigidMotion& setup : kSetups) {
    set_rigid(part.pts, setup);
    EXPECT_LT(max_residual(part.pts, pipeline::datum_alignment(part.pts, part.datums)), 1e-7);
  }
}

TEST(PartAlignment, DatumsDoNotSeeAnAddedRigidMotion) {
  Part part = block_part();
  set_random(part.pts, 5, 4.0);
  const PartPoints base = part.pts;
  const RigidMotion fit0 = pipeline::datum_alignment(base, part.datums);
  for (const RigidMotion& setup : kSetups) {
    PartPoints moved = base;
    add_rigid(moved, setup);
    const RigidMotion fit = pipeline::datum_alignment(moved, part.datums);
    expect_same_residuals(fit0, base, fit, moved, 1e-6);
  }
}

// After 3-2-1 with the block's faces: the top face's mean z residual, the side
// face's mean y residual and the end face's mean x residual are zero, and the
// top face is not tilted (no residual slope in x or y), nor the side face
// turned about z.
TEST(PartAlignment, DatumsPutTheFeaturesOnTheNominalOnes) {
  Part part = block_part();
  set_random(part.pts, 3, 4.0);
  // Plus a tilt and an offset the alignment must take out.
  add_rigid(part.pts, motion({30e-6, -20e-6, 40e-6}, {0.01, -0.02, 0.03}));
  const RigidMotion fit = pipeline::datum_alignment(part.pts, part.datums);
  auto residual = [&](std::size_t i) {
    return pipeline::aligned_deviation_um(fit, part.pts.nominal_mm[i], part.pts.deviation_um[i]);
  };
  auto mean_of = [&](const std::vector<std::size_t>& idx, int axis) {
    double s = 0;
    for (std::size_t i : idx) s += residual(i)(axis);
    return s / static_cast<double>(idx.size());
  };
  // Regression slope of the residual component `axis` against coordinate `along`.
  auto slope = [&](const std::vector<std::size_t>& idx, int axis, int along) {
    double mx = 0, mr = 0;
    for (std::size_t i : idx) {
      mx += part.pts.nominal_mm[i](along);
      mr += residual(i)(axis);
    }
    mx /= static_cast<double>(idx.size());
    mr /= static_cast<double>(idx.size());
    double sxy = 0, sxx = 0;
    for (std::size_t i : idx) {
      const double dx = part.pts.nominal_mm[i](along) - mx;
      sxy += dx * (residual(i)(axis) - mr);
      sxx += dx * dx;
    }
    return sxy / sxx;
  };
  EXPECT_NEAR(mean_of(part.datums.primary, 2), 0.0, 1e-6);
  // Slopes to 2e-5 µm/mm: the features are fitted to the predicted points
  // (total least squares), the regression here is on nominal coordinates;
  // the two differ by products of the deviations (measured up to 6e-6).
  EXPECT_NEAR(slope(part.datums.primary, 2, 0), 0.0, 2e-5);  // µm/mm
  EXPECT_NEAR(slope(part.datums.primary, 2, 1), 0.0, 2e-5);
  EXPECT_NEAR(mean_of(part.datums.secondary, 1), 0.0, 1e-6);
  EXPECT_NEAR(slope(part.datums.secondary, 1, 0), 0.0, 2e-5);
  EXPECT_NEAR(mean_of(part.datums.tertiary, 0), 0.0, 1e-6);
  // The rest of the part keeps a residual: the random errors are not rigid.
  EXPECT_GT(max_residual(part.pts, fit), 1.0);
}

TEST(PartAlignment, DatumsRefuseSetsThatDoNotDefineTheirFeature) {
  Part part = block_part();
  pipeline::DatumIndices d = part.datums;
  d.primary.resize(2);
  EXPECT_THROW(pipeline::datum_alignment(part.pts, d), pipeline::AlignmentError);
  d = part.datums;
  d.primary = {0, 1, 2, 3};  // one row of the top face: collinear
  EXPECT_THROW(pipeline::datum_alignment(part.pts, d), pipeline::AlignmentError);
  d = part.datums;
  d.secondary = {part.datums.primary[0], part.datums.primary[0]};
  EXPECT_THROW(pipeline::datum_alignment(part.pts, d), pipeline::AlignmentError);
  d = part.datums;
  d.tertiary.clear();
  EXPECT_THROW(pipeline::datum_alignment(part.pts, d), pipeline::AlignmentError);
}

TEST(PartAlignment, LineSets) {
  const auto s = pipeline::LineSet::parse("12-30,45,50-50", "--datum-primary");
  EXPECT_TRUE(s.contains(12));
  EXPECT_TRUE(s.contains(30));
  EXPECT_TRUE(s.contains(45));
  EXPECT_TRUE(s.contains(50));
  EXPECT_FALSE(s.contains(11));
  EXPECT_FALSE(s.contains(31));
  EXPECT_FALSE(s.contains(46));
  for (const char* bad : {"", "12-", "a", "30-12", "12,,13", "12 13"}) {
    try {
      pipeline::LineSet::parse(bad, "--datum-primary");
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().field, "--datum-primary");
      EXPECT_GT(e.where().column, 0u);
    }
  }
}

TEST(PartAlignment, RotationVectorOfTheMotion) {
  const RigidMotion m = motion({20e-6, -35e-6, 50e-6}, {0, 0, 0});
  EXPECT_LT((m.rotation_urad() - Vector3d{20, -35, 50}).norm(), 1e-9);
}

}  // namespace
}  // namespace abbe
