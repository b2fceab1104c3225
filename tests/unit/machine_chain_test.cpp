// Kinematic chain strings and the axis sets U(j) they imply.
#include <gtest/gtest.h>

#include <stdexcept>

#include "abbe/machine/kinematic_chain.hpp"
#include "model_test_machines.hpp"

namespace abbe::machine {
namespace {

// U(j) as a string of axis letters in X, Y, Z order.
std::string moved_by(const KinematicChain& c, Axis j) {
  std::string s;
  for (Axis i : kAxes)
    if (c.moves(j, i)) s += axis_letter(i);
  return s;
}

TEST(MachineChain, TableXColumnYZ) {
  auto c = KinematicChain::parse("w X' b Y Z t");
  EXPECT_EQ(c.order(), (std::array<Axis, 3>{Axis::x, Axis::y, Axis::z}));
  EXPECT_TRUE(c.workpiece_side(Axis::x));
  EXPECT_FALSE(c.workpiece_side(Axis::y));
  EXPECT_EQ(moved_by(c, Axis::x), "");
  EXPECT_EQ(moved_by(c, Axis::y), "XY");
  EXPECT_EQ(moved_by(c, Axis::z), "XYZ");
}

TEST(MachineChain, AllAxesOnTheToolSide) {
  auto c = KinematicChain::parse("w b X Y Z t");
  EXPECT_EQ(moved_by(c, Axis::x), "X");
  EXPECT_EQ(moved_by(c, Axis::y), "XY");
  EXPECT_EQ(moved_by(c, Axis::z), "XYZ");
}

TEST(MachineChain, CrossTable) {
  // X' carries Y' (Y' sits between the workpiece and X').
  auto c = KinematicChain::parse("w Y' X' b Z t");
  EXPECT_EQ(moved_by(c, Axis::y), "");
  EXPECT_EQ(moved_by(c, Axis::x), "Y");
  EXPECT_EQ(moved_by(c, Axis::z), "XYZ");
  auto m = c.moves_mask(Axis::x);
  EXPECT_EQ(m, (std::array<double, 3>{0.0, 1.0, 0.0}));
}

TEST(MachineChain, PrimesAreOptional) {
  auto c = KinematicChain::parse("  w Y X b   Z t ");
  EXPECT_TRUE(c.workpiece_side(Axis::x));
  EXPECT_EQ(moved_by(c, Axis::x), "Y");
}

TEST(MachineChain, AllTwentyFourChainsParse) {
  auto chains = test::all_chains();
  EXPECT_EQ(chains.size(), 24u);
  for (const auto& s : chains) EXPECT_NO_THROW(KinematicChain::parse(s)) << s;
}

TEST(MachineChain, RejectsInvalidChains) {
  for (const char* bad : {"", "w X b Y t", "X w b Y Z t", "w X b Y Z", "w X X b Z t",
                          "w X b Y Z b t", "w X Y Z t t", "w X' b Y' Z t", "w X' Y b Z t",
                          "w A b Y Z t", "w x b y z t", "w X b Y Z W t", "w X'' b Y Z t"}) {
    EXPECT_THROW(KinematicChain::parse(bad), std::invalid_argument) << "'" << bad << "'";
  }
}

}  // namespace
}  // namespace abbe::machine
