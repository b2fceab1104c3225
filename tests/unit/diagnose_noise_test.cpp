// The noise estimated apart from the model (noise.hpp): zero in, zero out;
// a known σ recovered from repeated points and from neighbour differences,
// with a trend along the run and a few gross outliers that must not
// inflate it.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "abbe/diagnose/noise.hpp"

namespace abbe::diagnose {
namespace {

// A run along X (set "run", 400 points, dx measured): y = trend + noise.
Problem run(double sigma, double trend_um_per_mm, bool repeat, int outliers) {
  Problem pb;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  const int points = 400;
  std::vector<double> y;
  for (int i = 0; i < points; ++i) {
    PointContext pc;
    const int k = repeat ? i % (points / 2) : i;  // repeat: the run measured twice
    pc.p = Eigen::Vector3d(2.5 * k, 0.0, 0.0);
    pc.s = pc.p;
    pc.dir = {1, 0, 0};
    pc.set = "run";
    pb.points.push_back(pc);
    Observation ob;
    ob.point = static_cast<std::uint32_t>(i);
    ob.u = Eigen::Vector3d::UnitX();
    pb.obs.push_back(ob);
    double v = trend_um_per_mm * pc.p.x() + sigma * n(rng);
    if (i % 97 == 13 && outliers-- > 0) v += 60.0;
    y.push_back(v);
  }
  pb.y = Eigen::Map<Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size()));
  pb.sets = {"run"};
  pb.direction_present = {true, false, false};
  return pb;
}

TEST(DiagnoseNoise, ZeroInZeroOut) {
  const NoiseEstimate e = estimate_noise(run(0.0, 0.0, false, 0));
  EXPECT_EQ(e.sigma_um, 0.0);
  EXPECT_EQ(e.method, "neighbour differences");
}

TEST(DiagnoseNoise, NeighbourDifferencesIgnoreATrendAndOutliers) {
  const NoiseEstimate e = estimate_noise(run(0.7, 0.01, false, 4));
  EXPECT_EQ(e.method, "neighbour differences");
  EXPECT_NEAR(e.sigma_um, 0.7, 0.08);
}

TEST(DiagnoseNoise, RepeatedPointsComeFirst) {
  const NoiseEstimate e = estimate_noise(run(0.5, 0.02, true, 3));
  EXPECT_EQ(e.method, "repeated points");
  EXPECT_EQ(e.pairs, 200u);
  EXPECT_NEAR(e.sigma_um, 0.5, 0.08);
}

TEST(DiagnoseNoise, TooFewDifferencesGiveNoEstimate) {
  Problem pb = run(0.5, 0.0, false, 0);
  pb.points.resize(5);
  pb.obs.resize(5);
  pb.y.conservativeResize(5);
  const NoiseEstimate e = estimate_noise(pb);
  EXPECT_EQ(e.method, "none");
  EXPECT_EQ(e.sigma_um, 0.0);
}

// A 13 × 9 plate (50 mm pitch, dx and dy) set up 500 µrad rotated, noise
// 0.5 µm; its holes in row order (serpentine) or in a scattered order (as
// a plate's drilling order lists them).
Problem plate(bool scattered) {
  std::vector<Eigen::Vector3d> holes;
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < 13; ++c) holes.emplace_back(50.0 * (r % 2 ? 12 - c : c), 50.0 * r, 0.0);
  std::mt19937_64 rng(11);
  if (scattered) std::shuffle(holes.begin(), holes.end(), rng);
  std::normal_distribution<double> n(0.0, 0.5);
  Problem pb;
  std::vector<double> y;
  for (const Eigen::Vector3d& p : holes) {
    PointContext pc;
    pc.p = p;
    pc.s = p;
    pc.set = "plate";
    pb.points.push_back(pc);
    for (int i = 0; i < 2; ++i) {
      Observation ob;
      ob.point = static_cast<std::uint32_t>(pb.points.size() - 1);
      ob.u = i == 0 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
      pb.obs.push_back(ob);
      // A rotation θ about Z: d = θ·(−y, x), θ = 500 µrad (µm per mm: 0.5).
      y.push_back(0.5 * (i == 0 ? -p.y() : p.x()) + n(rng));
    }
  }
  pb.y = Eigen::Map<Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size()));
  pb.sets = {"plate"};
  pb.direction_present = {true, true, false};
  return pb;
}

TEST(DiagnoseNoise, RowsOfAPlateGiveTheNoiseWhateverItsRotation) {
  const NoiseEstimate e = estimate_noise(plate(false));
  EXPECT_EQ(e.method, "neighbour differences");
  EXPECT_NEAR(e.sigma_um, 0.5, 0.1);
}

// Holes in no spatial order: a second difference of three of them holds the
// rotation's 0.5 µm per mm over hundreds of mm, not the noise (it gave
// σ ≈ 77 µm before only equally spaced runs counted).
TEST(DiagnoseNoise, ScatteredPointsGiveNoEstimate) {
  const NoiseEstimate e = estimate_noise(plate(true));
  EXPECT_EQ(e.method, "none") << e.sigma_um << " µm from " << e.pairs << " differences";
  EXPECT_EQ(e.sigma_um, 0.0);
}

}  // namespace
}  // namespace abbe::diagnose
