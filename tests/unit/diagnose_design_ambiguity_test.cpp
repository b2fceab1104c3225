// What the measurement design cannot tell apart (design_ambiguity.hpp):
// levelled axes, a cycle beside other functions of the same levels, and an
// effect that is the growth of a reversal along its travel. Hand-made
// problems with known answers.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>

#include "abbe/diagnose/design_ambiguity.hpp"
#include "abbe/diagnose/diagnosis.hpp"
#include "diagnose_test_problem.hpp"

namespace abbe::diagnose {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Points with dx and dy observed; y filled by `truth` plus noise.
template <class Truth>
Problem make_problem(const std::vector<PointContext>& pts, Truth truth, std::uint64_t seed) {
  Problem pb;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.5);
  std::vector<double> y;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (const PointContext& pc : pts) {
    const auto p = static_cast<std::uint32_t>(pb.points.size());
    pb.points.push_back(pc);
    const Eigen::Vector3d d = truth(pc);
    for (int i = 0; i < 2; ++i) {
      Observation ob;
      ob.point = p;
      ob.u = Eigen::Vector3d::Unit(i);
      pb.obs.push_back(ob);
      y.push_back(d[i] + noise(rng));
    }
    lo = lo.cwiseMin(pc.s);
    hi = hi.cwiseMax(pc.s);
  }
  test::finish_problem(pb, y, "a", {true, true, false}, lo, hi);
  return pb;
}

PointContext at(double x, double y, int vx = 1, int vy = 1) {
  PointContext pc;
  pc.p = {x, y, 0.0};
  pc.s = pc.p;
  pc.dir = {vx, vy, 0};
  pc.set = "a";
  return pc;
}

// A regular plate: 12 × 8 levels 50 mm apart.
std::vector<PointContext> regular() {
  std::vector<PointContext> v;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 12; ++i) v.push_back(at(50.0 * i, 50.0 * j));
  return v;
}

// The same box at irregular positions.
std::vector<PointContext> irregular() {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> ux(0.0, 550.0), uy(0.0, 350.0);
  std::vector<PointContext> v;
  for (int k = 0; k < 96; ++k) v.push_back(at(ux(rng), uy(rng)));
  return v;
}

SelectedTerm fitted(Term t, std::vector<double> coef) {
  SelectedTerm st;
  t.coef = std::move(coef);
  t.stderr_.assign(t.coef.size(), 0.01);
  st.term = std::move(t);
  return st;
}

// A term of `kind` along `axis`, in its own direction.
Term term(TermKind kind, int axis, double period_mm = 0.0) {
  Term t = test::make_term(kind, axis, axis);
  t.period_mm = period_mm;
  return t;
}
Term scale(int axis) { return term(TermKind::scale, axis); }
Term cyclic(int axis, double period) { return term(TermKind::cyclic, axis, period); }
Term reversal(int axis) { return term(TermKind::reversal, axis); }

TEST(DiagnoseDesignAmbiguity, RegularLevelsAreFoundAndIrregularPositionsAreNot) {
  const Problem reg = make_problem(
      regular(), [](const PointContext&) { return Eigen::Vector3d::Zero(); }, 1);
  const auto lv = levelled_axes(reg, {}, 4.0);
  EXPECT_EQ(lv[0].size(), 12u);
  EXPECT_EQ(lv[1].size(), 8u);
  EXPECT_TRUE(lv[2].empty());  // one level: nothing to alias
  // Levels 50 mm apart alias the periods below 100 mm: they count while the
  // catalogue's shortest period is at most half their gap.
  EXPECT_EQ(levelled_axes(reg, {}, 25.0)[0].size(), 12u);
  EXPECT_TRUE(levelled_axes(reg, {}, 26.0)[0].empty());
  const Problem irr = make_problem(
      irregular(), [](const PointContext&) { return Eigen::Vector3d::Zero(); }, 1);
  const auto li = levelled_axes(irr, {}, 4.0);
  EXPECT_TRUE(li[0].empty());
  EXPECT_TRUE(li[1].empty());
}

// A pitch error of X (18 mm, with its harmonic) on 50 mm levels, selected as
// a scale X and a cycle of X: one function of the 12 levels, both ambiguous.
TEST(DiagnoseDesignAmbiguity, ScaleBesideACycleOfALevelledAxisIsAmbiguous) {
  auto pitch = [](const PointContext& pc) {
    const double w = 2.0 * kPi * pc.s.x() / 18.0;
    return Eigen::Vector3d(4.0 * (std::sin(w) + 0.35 * std::sin(2.0 * w + 1.0)), 0.0, 0.0);
  };
  for (const bool reg : {true, false}) {
    const Problem pb = make_problem(reg ? regular() : irregular(), pitch, 2);
    std::vector<SelectedTerm> eff{fitted(scale(0), {3.0}), fitted(cyclic(0, 97.5), {1.0, 0.5})};
    const auto log = mark_design_ambiguities(pb, {}, eff, {}, 4.0);
    auto has = [](const SelectedTerm& st, const std::string& alt) {
      return std::find(st.ambiguous_with.begin(), st.ambiguous_with.end(), alt) !=
             st.ambiguous_with.end();
    };
    if (reg) {
      // One line for the pair, one for the cycle's period (another fits the
      // 50 mm levels as well: the cycle period test).
      ASSERT_EQ(log.size(), 2u);
      ASSERT_FALSE(eff[0].ambiguous_with.empty());
      EXPECT_EQ(eff[0].ambiguous_with[0], "cyclic X→X (97.50 mm)");
      EXPECT_NE(eff[0].separate_by.find("sample X at irregular spacing"), std::string::npos);
      EXPECT_TRUE(has(eff[1], "scale X"));
    } else {
      EXPECT_TRUE(log.empty());
      EXPECT_TRUE(eff[0].ambiguous_with.empty());
      EXPECT_TRUE(eff[1].ambiguous_with.empty());
    }
  }
}

// A scale of X beside a cycle of Y: different levels, nothing shared.
TEST(DiagnoseDesignAmbiguity, EffectsOfDifferentAxesStayNamed) {
  const Problem pb = make_problem(
      regular(), [](const PointContext&) { return Eigen::Vector3d::Zero(); }, 3);
  std::vector<SelectedTerm> eff{fitted(scale(0), {3.0}), fitted(cyclic(1, 40.0), {1.0, 0.5})};
  for (const std::string& line : mark_design_ambiguities(pb, {}, eff, {}, 4.0))
    EXPECT_EQ(line.find("scale X"), std::string::npos) << line;
  EXPECT_TRUE(eff[0].ambiguous_with.empty());
}

// Its period not the data's: ambiguous, or named with the period unresolved.
bool period_not_told(const SelectedTerm& st) {
  return !st.ambiguous_with.empty() || !st.other_periods_mm.empty();
}

// The cycle period test: a pitch error of X (4 µm) measured at the levels
// of X only. On 24 irregular levels its period (13 mm) is the data's: no
// other period of 4–100 mm fits the levels as well, and the cycle stays
// named. On 12 regular levels 50 mm apart every period aliases: another
// period fits as well. Its kind may still be the data's: at 14.71 mm
// (= 50/3.4) the samples are a wave of 125 mm (the alias at that spacing)
// that no smooth function of x follows, and the cycle is named with its
// period unresolved; at 13 mm they are a wave of 325 mm that a polynomial
// of degree 6 follows, and the cycle is ambiguous with any function of x.
TEST(DiagnoseDesignAmbiguity, ACycleIsNamedOnlyWhereTheLevelsFixItsPeriod) {
  double period = 13.0;
  auto pitch = [&period](const PointContext& pc) {
    return Eigen::Vector3d(4.0 * std::sin(2.0 * kPi * pc.s.x() / period + 0.4), 0.0, 0.0);
  };
  auto levels_of_x = [](int levels, bool jitter) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> shift(-0.3, 0.3);
    std::vector<PointContext> v;
    const double step = 550.0 / (levels - 1);
    for (int i = 0; i < levels; ++i) {
      const double x = step * (i + (jitter && i > 0 && i < levels - 1 ? shift(rng) : 0.0));
      for (int j = 0; j < 8; ++j) v.push_back(at(x, 50.0 * j));
    }
    return v;
  };
  struct Design {
    int levels;
    bool jitter;
    double period;
    bool period_unresolved, ambiguous;
  };
  for (const Design d :
       {Design{24, true, 13.0, false, false}, Design{12, false, 50.0 / 3.4, true, false},
        Design{12, false, 13.0, false, true}}) {
    period = d.period;
    const Problem pb = make_problem(levels_of_x(d.levels, d.jitter), pitch, 5);
    std::vector<SelectedTerm> eff{fitted(cyclic(0, d.period), {4.0, 0.0})};
    const auto log = mark_design_ambiguities(pb, {}, eff, {}, 4.0);
    const std::string what =
        fmt::format("{} levels{}, {} mm", d.levels, d.jitter ? " irregular" : " regular", d.period);
    EXPECT_EQ(!eff[0].other_periods_mm.empty(), d.period_unresolved) << what;
    EXPECT_EQ(!eff[0].ambiguous_with.empty(), d.ambiguous) << what;
    if (d.period_unresolved || d.ambiguous) {
      ASSERT_FALSE(log.empty());
      EXPECT_NE(
          log[0].find(d.ambiguous ? "is not told from a cycle at" : "its period not resolved"),
          std::string::npos)
          << log[0];
      EXPECT_NE(eff[0].separate_by.find("measure X at more positions"), std::string::npos);
    }
    if (d.ambiguous) {
      EXPECT_NE(std::find(eff[0].ambiguous_with.begin(), eff[0].ambiguous_with.end(),
                          "any function of x on its 12 levels"),
                eff[0].ambiguous_with.end());
    }
  }
}

// A cycle named with its period unresolved, in the reports: the text says
// so beside the effect ("NAMED, ITS PERIOD NOT"), with what would resolve
// it; the JSON keeps the status "named" and lists the other periods.
TEST(DiagnoseDesignAmbiguity, ACycleWithItsPeriodUnresolvedInTheReports) {
  const double period = 50.0 / 3.4;
  std::vector<PointContext> pts;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 8; ++j) pts.push_back(at(50.0 * i, 50.0 * j));
  const Problem pb = make_problem(
      pts,
      [&](const PointContext& pc) {
        return Eigen::Vector3d(4.0 * std::sin(2.0 * kPi * pc.s.x() / period + 0.4), 0.0, 0.0);
      },
      5);
  Diagnosis d;
  d.model = "ae-arm";
  d.effects = {fitted(cyclic(0, period), {4.0, 0.0})};
  d.effects[0].term.stderr_ = {0.05, 0.05};
  mark_design_ambiguities(pb, {}, d.effects, {}, 4.0);
  ASSERT_TRUE(d.effects[0].ambiguous_with.empty());
  ASSERT_FALSE(d.effects[0].other_periods_mm.empty());
  const std::string text = report_text(d);
  EXPECT_NE(text.find("NAMED, ITS PERIOD NOT: period not resolved: "), std::string::npos) << text;
  EXPECT_NE(text.find("to resolve it: measure X at more positions"), std::string::npos) << text;
  EXPECT_EQ(text.find("AMBIGUOUS"), std::string::npos) << text;
  const auto j = nlohmann::json::parse(report_json(d));
  const auto& e = j.at("effects").at(0);
  EXPECT_EQ(e.at("status"), "named");
  EXPECT_EQ(e.at("other_periods_mm").get<std::vector<double>>(), d.effects[0].other_periods_mm);
  EXPECT_TRUE(e.at("ambiguous_with").empty());
  // Resolved: no such line, no such key.
  d.effects[0].other_periods_mm.clear();
  EXPECT_EQ(report_text(d).find("PERIOD NOT"), std::string::npos);
  EXPECT_FALSE(
      nlohmann::json::parse(report_json(d)).at("effects").at(0).contains("other_periods_mm"));
}

// A cycle whose other periods become alternatives (once it has a rival,
// rival_check.cpp, or its kind is not told): the same cycle at each of
// them, no other period left.
TEST(DiagnoseDesignAmbiguity, OtherPeriodsBecomeAlternatives) {
  SelectedTerm st = fitted(cyclic(0, 13.0), {4.0, 0.0});
  st.other_periods_mm = {5.47, 31.2};
  st.ambiguous_with = {"scale X"};
  periods_as_alternatives(st);
  EXPECT_TRUE(st.other_periods_mm.empty());
  ASSERT_EQ(st.ambiguous_with.size(), 3u);
  EXPECT_EQ(st.ambiguous_with[0], "scale X");
  Term at = st.term;
  at.period_mm = 5.47;
  EXPECT_EQ(st.ambiguous_with[1], at.label());
  at.period_mm = 31.2;
  EXPECT_EQ(st.ambiguous_with[2], at.label());
  periods_as_alternatives(st);  // nothing left to move
  EXPECT_EQ(st.ambiguous_with.size(), 3u);
}

// A period that rests on one level (level_out_test): a 13 mm pitch error
// of X read at 9 levels 50 mm apart, where its aliases give the same
// samples, and at two more levels off that grid (163 and 437 mm). With all
// eleven levels no other period fits as well (the cycle is named without
// the test); with one off-grid level alone a cycle at 6.1 mm does, so
// leaving out either of them shows that the period rests on it: the cycle
// (its kind the data's, no smooth function of x follows its samples) is
// named with its period unresolved.
TEST(DiagnoseDesignAmbiguity, APeriodThatRestsOnOneLevelIsNotResolved) {
  auto pitch = [](const PointContext& pc) {
    return Eigen::Vector3d(4.0 * std::sin(2.0 * kPi * pc.s.x() / 13.0 + 0.4), 0.0, 0.0);
  };
  std::vector<PointContext> pts;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j < 8; ++j)
      pts.push_back(at(i < 9 ? 50.0 * i : (i == 9 ? 437.0 : 163.0), 50.0 * j));
  const Problem pb = make_problem(pts, pitch, 5);
  DesignAmbiguityOptions without_test;
  without_test.level_out_test = false;
  std::vector<SelectedTerm> with{fitted(cyclic(0, 13.0), {4.0, 0.0})}, without = with;
  const auto log = mark_design_ambiguities(pb, {}, with, {}, 4.0);
  mark_design_ambiguities(pb, {}, without, without_test, 4.0);
  EXPECT_FALSE(period_not_told(without[0]));
  EXPECT_TRUE(with[0].ambiguous_with.empty());
  ASSERT_EQ(with[0].other_periods_mm.size(), 1u);
  ASSERT_FALSE(log.empty());
  const bool on_163 = log[0].find("without the level x = 163 mm") != std::string::npos;
  const bool on_437 = log[0].find("without the level x = 437 mm") != std::string::npos;
  EXPECT_TRUE(on_163 || on_437) << log[0];
  EXPECT_NE(with[0].separate_by.find(on_163 ? "without the level x = 163 mm"
                                            : "without the level x = 437 mm"),
            std::string::npos)
      << with[0].separate_by;
}

// The margin another period must come within is the noise of a function of
// the levels (DesignAmbiguityOptions::level_noise_margin). A 2 µm pitch
// error of 13 mm on 12 irregular levels of X, each level read 8 times
// (noise 0.5 µm), with an error of each level that repeats in all its
// readings (0.5 µm rms, as the model's own table error at a laser target
// does): the levels' values scatter more than the readings, and another
// period fits within that scatter in 18 of 20 draws (12 of 20 with σ̂²
// alone; 7 and 2 before each level was also left out in turn).
// The margin is never below σ̂²'s: a cycle ambiguous without it is ambiguous
// with it. Without the levels' error the decisions are the same.
TEST(DiagnoseDesignAmbiguity, TheCyclePeriodMarginIsTheNoiseOfTheLevels) {
  const std::vector<double> xs = [] {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> shift(-0.3, 0.3);
    std::vector<double> v;
    for (int i = 0; i < 12; ++i) v.push_back(50.0 * (i + (i > 0 && i < 11 ? shift(rng) : 0.0)));
    return v;
  }();
  std::vector<PointContext> pts;
  for (double x : xs)
    for (int j = 0; j < 8; ++j) pts.push_back(at(x, 50.0 * j));
  DesignAmbiguityOptions readings_only;
  readings_only.level_noise_margin = false;
  const int draws = 20;
  for (const double level_error : {0.5, 0.0}) {
    int ambiguous_with = 0, ambiguous_without = 0, same = 0;
    for (int k = 0; k < draws; ++k) {
      std::mt19937_64 rng(static_cast<std::uint64_t>(100 + k));
      std::normal_distribution<double> n(0.0, level_error);
      std::vector<double> e;
      for (std::size_t l = 0; l < xs.size(); ++l) e.push_back(n(rng));
      auto truth = [&](const PointContext& pc) {
        const auto at_level = std::min_element(xs.begin(), xs.end(), [&](double a, double b) {
          return std::abs(a - pc.s.x()) < std::abs(b - pc.s.x());
        });
        const double level = e[static_cast<std::size_t>(at_level - xs.begin())];
        return Eigen::Vector3d(2.0 * std::sin(2.0 * kPi * pc.s.x() / 13.0 + 0.4) + level, 0.0, 0.0);
      };
      const Problem pb = make_problem(pts, truth, static_cast<std::uint64_t>(7 + k));
      std::vector<SelectedTerm> with{fitted(cyclic(0, 13.0), {2.0, 0.0})}, without = with;
      mark_design_ambiguities(pb, {}, with, {}, 4.0);
      mark_design_ambiguities(pb, {}, without, readings_only, 4.0);
      const bool a_with = period_not_told(with[0]);
      const bool a_without = period_not_told(without[0]);
      ambiguous_with += a_with ? 1 : 0;
      ambiguous_without += a_without ? 1 : 0;
      same += with[0].ambiguous_with == without[0].ambiguous_with &&
                      with[0].other_periods_mm == without[0].other_periods_mm
                  ? 1
                  : 0;
      EXPECT_TRUE(a_with || !a_without) << "draw " << k << ": the margin fell below σ̂²'s";
    }
    std::cout << "level error " << level_error << " µm: ambiguous " << ambiguous_with << "/"
              << draws << " with the levels' noise, " << ambiguous_without << "/" << draws
              << " with σ̂² alone\n";
    if (level_error > 0.0) {
      EXPECT_GE(ambiguous_with, ambiguous_without + 3);
    } else {
      EXPECT_EQ(same, draws);
    }
  }
}

// A reversal of Y growing 20 % along Y, on a design that drives Y one way
// except for its first row (a plate's rows): the scale Y selected beside the
// reversal is the growth as much, and is ambiguous. Walked both ways (each
// point approached from either side at random), the growth and a real scale
// differ and the scale stays named.
TEST(DiagnoseDesignAmbiguity, ScaleBesideAReversalThatGrowsAlongItsTravel) {
  for (const bool one_way : {true, false}) {
    std::vector<PointContext> pts;
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int j = 0; j < 9; ++j)
      for (int i = 0; i < 13; ++i) {
        const int vy = one_way ? (j == 0 ? -1 : 1) : (u(rng) < 0.5 ? -1 : 1);
        pts.push_back(at(37.0 * i + 3.0 * u(rng), 41.0 * j + 3.0 * u(rng), 1, vy));
      }
    // One way: the growing reversal alone; both ways: a reversal and a real
    // scale (2 µm over the plate).
    auto truth = [one_way](const PointContext& pc) {
      const double u = (pc.s.y() - 170.0) / 170.0;
      if (one_way) return Eigen::Vector3d(0.0, 3.0 * pc.dir[1] * (1.0 + 0.2 * u), 0.0);
      return Eigen::Vector3d(0.0, 3.0 * pc.dir[1] + 2.0 * u, 0.0);
    };
    const Problem pb = make_problem(pts, truth, 6);
    std::vector<SelectedTerm> eff{fitted(reversal(1), {6.0}), fitted(scale(1), {1.0})};
    DesignAmbiguityOptions o;
    o.levelled_axes = false;
    mark_design_ambiguities(pb, {}, eff, o, 4.0);
    EXPECT_TRUE(eff[0].ambiguous_with.empty());
    if (one_way) {
      ASSERT_EQ(eff[1].ambiguous_with.size(), 1u);
      EXPECT_EQ(eff[1].ambiguous_with[0], "reversal Y→Y growing along y");
      EXPECT_NE(eff[1].separate_by.find("drive Y both ways"), std::string::npos);
    } else {
      EXPECT_TRUE(eff[1].ambiguous_with.empty());
    }
  }
}

// A reversal of X growing along x, read along two face diagonals of XY
// driven there and back (every target approached in X and Y at once, as
// along a body diagonal): each axis's jump projects as the same step on
// both lines, so the jump of Y beside the same growth of X fits as well —
// the growth tells X, the jump does not, and the reversal of Y is an
// alternative of the jump. Where the data hold no jump (the growth alone),
// whose jump it is does not arise: no alternative. Approached in X and Y
// independently (at random), the two jumps differ and the growing reversal
// stays named.
TEST(DiagnoseDesignAmbiguity, AGrowingReversalsJumpIsTheJumpOfEveryAxisThatReversesWithIt) {
  const Eigen::Vector3d lo(0.0, 0.0, 0.0), hi(400.0, 300.0, 0.0);
  Term grown = test::make_term(TermKind::reversal, 0, 0);
  grown.degree = 1;
  grown.centre = 0.5 * (lo + hi);
  grown.half = (0.5 * (hi - lo)).cwiseMax(1e-9);
  for (const auto& [together, jump] : {std::pair{true, 3.0}, {true, 0.0}, {false, 3.0}}) {
    Problem pb;
    std::vector<double> y;
    std::mt19937_64 rng(8);
    std::normal_distribution<double> noise(0.0, 0.3);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    const std::array<std::pair<Eigen::Vector3d, Eigen::Vector3d>, 2> lines{
        std::pair{lo, hi},
        std::pair{Eigen::Vector3d(400.0, 0.0, 0.0), Eigen::Vector3d(0.0, 300.0, 0.0)}};
    for (const auto& [a, e] : lines)
      for (int run = 0; run < 3; ++run)
        for (const int way : {1, -1})
          for (int k = 0; k <= 20; ++k) {
            const double f = way > 0 ? k / 20.0 : 1.0 - k / 20.0;
            const Eigen::Vector3d u = (e - a).normalized();
            PointContext pc;
            pc.p = pc.s = a + f * (e - a);
            pc.set = "a";
            for (int i = 0; i < 2; ++i)
              pc.dir[static_cast<std::size_t>(i)] =
                  together ? (way * u[i] > 0.0 ? 1 : -1) : (u01(rng) < 0.5 ? -1 : 1);
            // A jump of X growing by 1 µm to the end of x's travel.
            const double dx =
                0.5 * pc.dir[0] * (jump + 1.0 * (pc.s.x() - grown.centre.x()) / grown.half.x());
            test::add_reading(pb, y, pc, u, u.x() * dx + noise(rng));
          }
    test::finish_problem(pb, y, "a", {true, true, false}, lo, hi);
    std::vector<SelectedTerm> eff{fitted(grown, {jump, 1.0})}, off = eff;
    DesignAmbiguityOptions o;
    o.levelled_axes = false;
    const auto log = mark_design_ambiguities(pb, {}, eff, o, 4.0);
    DesignAmbiguityOptions without = o;
    without.reversal_jump = false;
    mark_design_ambiguities(pb, {}, off, without, 4.0);
    EXPECT_TRUE(off[0].ambiguous_with.empty());
    if (together && jump > 0.0) {
      ASSERT_EQ(eff[0].ambiguous_with.size(), 1u);
      EXPECT_EQ(eff[0].ambiguous_with[0], "reversal Y→Y (its jump)");
      EXPECT_NE(eff[0].separate_by.find("measure the reversal of each axis on its own"),
                std::string::npos)
          << eff[0].separate_by;
      EXPECT_NE(eff[0].separate_by.find("the growth along x is X's"), std::string::npos)
          << eff[0].separate_by;
    } else {
      EXPECT_TRUE(eff[0].ambiguous_with.empty()) << eff[0].ambiguous_with.front();
    }
  }
}

// A drift of Z in time on a grid whose 5 Z levels are walked in order (one
// pass: time and z go together) is told from any function of z on the
// levels only by its course within each level. Where that course is below
// the noise (a slow drift, 0.3 µm within a level, 0.5 µm noise) the drift is
// ambiguous with the levels ("measure in another order"); where the data
// show it (a drift that saturates, 0.05 µm noise) the drift stays named, as
// it does walked there and back (each level at two times).
TEST(DiagnoseDesignAmbiguity, DriftOnLevelsWalkedInOrderIsToldByItsCourseWithinALevel) {
  enum Case { slow_one_pass, clean_one_pass, clean_there_and_back };
  for (const Case c : {slow_one_pass, clean_one_pass, clean_there_and_back}) {
    const bool one_pass = c != clean_there_and_back;
    std::vector<PointContext> pts;
    for (int pass = 0; pass < (one_pass ? 1 : 2); ++pass)
      for (int kz = 0; kz < 5; ++kz)
        for (int i = 0; i < 20; ++i) {
          const int level = pass == 0 ? kz : 4 - kz;
          PointContext pc = at(30.0 * i, 0.0);
          pc.p.z() = pc.s.z() = 100.0 * level;
          pc.t = 10.0 * static_cast<double>(pts.size());
          pts.push_back(pc);
        }
    std::mt19937_64 rng(9);
    std::normal_distribution<double> noise(0.0, c == slow_one_pass ? 0.5 : 0.05);
    Problem pb;
    std::vector<double> y;
    for (const PointContext& pc : pts) {
      const double d =
          c == slow_one_pass ? 1.5 * pc.t / 1000.0 : -3.0 * (1.0 - std::exp(-pc.t / 600.0));
      test::add_reading(pb, y, pc, Eigen::Vector3d::UnitZ(), d + noise(rng));
    }
    test::finish_problem(pb, y, "a", {false, false, true}, {0.0, 0.0, 0.0}, {570.0, 0.0, 400.0});
    pb.var_lo[3] = 0.0;
    pb.var_hi[3] = pts.back().t;
    Term drift;
    drift.kind = TermKind::thermal_drift;
    drift.axis = 2;
    drift.direction = 2;
    drift.tau_s = c == slow_one_pass ? 0.0 : 600.0;
    std::vector<SelectedTerm> eff{fitted(drift, {-3.0})};
    mark_design_ambiguities(pb, {}, eff, {}, 4.0);
    if (c == slow_one_pass) {
      ASSERT_EQ(eff[0].ambiguous_with.size(), 1u);
      EXPECT_NE(eff[0].ambiguous_with[0].find("z"), std::string::npos) << eff[0].ambiguous_with[0];
      EXPECT_NE(eff[0].separate_by.find("another order or after a pause"), std::string::npos);
    } else {
      EXPECT_TRUE(eff[0].ambiguous_with.empty()) << c << ": " << eff[0].ambiguous_with.front();
    }
  }
}

// dz read at `levels` Z levels 100 mm apart, 20 points per level 30 mm apart
// in x, walked level by level in order (10 s per point): time follows z.
template <class Truth>
Problem levels_in_order(int levels, Truth truth, double noise_um, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_um);
  Problem pb;
  std::vector<double> y;
  for (int kz = 0; kz < levels; ++kz)
    for (int i = 0; i < 20; ++i) {
      PointContext pc = at(30.0 * i, 0.0);
      pc.p.z() = pc.s.z() = 100.0 * kz;
      pc.t = 10.0 * static_cast<double>(pb.points.size());
      test::add_reading(pb, y, pc, Eigen::Vector3d::UnitZ(), truth(pc) + noise(rng));
    }
  test::finish_problem(pb, y, "a", {false, false, true}, {0.0, 0.0, 0.0},
                       {570.0, 0.0, 100.0 * (levels - 1)});
  pb.var_lo[3] = 0.0;
  pb.var_hi[3] = pb.points.back().t;
  return pb;
}

// On 3 (or 4) levels a cycle of Z with its period, phase and amplitude free
// fits any values of the levels: a scale of Z there is a pitch error of Z
// as much, whatever the data. On 6 levels it is not (with time in the data
// the drift test alone decides; here the scale is clean and well resolved).
TEST(DiagnoseDesignAmbiguity, AScaleOnThreeLevelsIsAPitchErrorAsMuch) {
  for (const int levels : {3, 4, 6}) {
    const Problem pb = levels_in_order(
        levels, [](const PointContext& pc) { return 0.02 * pc.s.z(); }, 0.05, 7);
    std::vector<SelectedTerm> eff{fitted(scale(2), {1.0})};
    mark_design_ambiguities(pb, {}, eff, {}, 4.0);
    if (levels <= 4) {
      ASSERT_EQ(eff[0].ambiguous_with.size(), 2u) << levels;
      EXPECT_NE(eff[0].ambiguous_with[0].find("cyclic Z→Z"), std::string::npos);
      EXPECT_NE(eff[0].separate_by.find("more levels"), std::string::npos);
    } else {
      EXPECT_TRUE(eff[0].ambiguous_with.empty()) << eff[0].ambiguous_with.front();
    }
  }
}

// Time follows the 5 Z levels. A slow drift of Z in time (within each level
// it moves by 1/5 of its course, below what 0.5 µm noise shows), selected
// as a scale of Z: a drift in its place fits as well — ambiguous, "measure
// in another order". A clean scale of Z (0.05 µm noise) rejects the drift,
// whose course within each level the data do not show: it stays named.
TEST(DiagnoseDesignAmbiguity, AScaleWhereTimeFollowsTheLevelsIsTestedAgainstADrift) {
  for (const bool drift : {true, false}) {
    const Problem pb = levels_in_order(
        5,
        [drift](const PointContext& pc) { return drift ? 2.0 * pc.t / 1000.0 : 0.005 * pc.s.z(); },
        drift ? 0.5 : 0.05, 8);
    std::vector<SelectedTerm> eff{fitted(scale(2), {1.0})};
    const auto log = mark_design_ambiguities(pb, {}, eff, {}, 4.0);
    if (drift) {
      ASSERT_EQ(eff[0].ambiguous_with.size(), 1u);
      EXPECT_EQ(eff[0].ambiguous_with[0], "thermal_drift t→Z");
      EXPECT_NE(eff[0].separate_by.find("another order"), std::string::npos);
    } else {
      EXPECT_TRUE(eff[0].ambiguous_with.empty()) << eff[0].ambiguous_with.front();
      EXPECT_TRUE(log.empty());
    }
  }
}

// A raster in XY (30 rows along X, 5 mm apart in Y — closer than twice the
// shortest period, so Y is not levelled — 20 points 30 mm apart per row,
// serpentine, 2 s per point), dy read: time follows y (`shuffled`: the
// same points in a random order in time, so it does not).
template <class Truth>
Problem raster(Truth truth, bool shuffled, std::uint64_t seed) {
  std::vector<PointContext> pts;
  for (int row = 0; row < 30; ++row)
    for (int i = 0; i < 20; ++i)
      pts.push_back(at(30.0 * (row % 2 == 0 ? i : 19 - i), 5.0 * row, row % 2 == 0 ? 1 : -1, 1));
  std::vector<double> times(pts.size());
  for (std::size_t k = 0; k < pts.size(); ++k) times[k] = 2.0 * static_cast<double>(k);
  if (shuffled) std::shuffle(times.begin(), times.end(), std::mt19937_64(seed + 1));
  for (std::size_t k = 0; k < pts.size(); ++k) pts[k].t = times[k];
  Problem pb = make_problem(pts, truth, seed);
  pb.var_lo[3] = 0.0;
  pb.var_hi[3] = 2.0 * static_cast<double>(pts.size() - 1);
  return pb;
}

// The datum: an offset of set "a" in X and in Y.
std::vector<SelectedTerm> offsets() {
  std::vector<SelectedTerm> out;
  for (int i = 0; i < 2; ++i) {
    Term t;
    t.kind = TermKind::setup_offset;
    t.axis = t.direction = i;
    t.set = "a";
    out.push_back(fitted(t, {0.0}));
  }
  return out;
}

Term drift_with_x(double tau) {
  Term t;
  t.kind = TermKind::thermal_drift;
  t.axis = t.with_axis = 0;
  t.direction = 1;
  t.tau_s = tau;
  return t;
}

// Where time follows an axis the design does not level (a raster's rows),
// a drift ∝ x·t of Y and an off-centre coupling x·y→Y are one structure:
// the drift named in the coupling's place is ambiguous with it ("measure in
// another order"), and a coupling named in a drift's place with the drift.
// A drift whose course the static terms cannot follow (τ 200 s of a 20 min
// raster) stays named, and where time does not follow y the test does not
// run.
TEST(DiagnoseDesignAmbiguity, ADriftWhereTimeFollowsARasterIsTestedAgainstTheStaticTerms) {
  auto coupling = [](const PointContext& pc) {
    return Eigen::Vector3d(0.0, 2e-4 * (pc.s.x() - 100.0) * (pc.s.y() - 30.0), 0.0);
  };
  for (const bool shuffled : {false, true}) {
    const Problem pb = raster(coupling, shuffled, 3);
    std::vector<SelectedTerm> eff{fitted(drift_with_x(0.0), {1.0})};
    const auto log = mark_design_ambiguities(pb, offsets(), eff, {}, 4.0);
    if (!shuffled) {
      ASSERT_EQ(eff[0].ambiguous_with.size(), 1u);
      EXPECT_NE(eff[0].ambiguous_with[0].find("coupling x·y→Y"), std::string::npos)
          << eff[0].ambiguous_with[0];
      EXPECT_NE(eff[0].separate_by.find("another order"), std::string::npos);
      ASSERT_EQ(log.size(), 1u);
      EXPECT_NE(log[0].find("time follows y"), std::string::npos) << log[0];
    } else {
      EXPECT_TRUE(eff[0].ambiguous_with.empty()) << eff[0].ambiguous_with.front();
    }
  }
  {
    const Problem pb = raster(
        [](const PointContext& pc) {
          return Eigen::Vector3d(0.0, 6.0 * pc.s.x() / 570.0 * pc.t / 1200.0, 0.0);
        },
        false, 4);
    Term c = test::make_term(TermKind::coupling, 0, 1);
    c.with_axis = 1;
    c.centre = pb.travel_mid;
    c.half = pb.travel_half;
    std::vector<SelectedTerm> eff{fitted(c, {1.0})};
    mark_design_ambiguities(pb, offsets(), eff, {}, 4.0);
    ASSERT_EQ(eff[0].ambiguous_with.size(), 1u);
    EXPECT_NE(eff[0].ambiguous_with[0].find("thermal_drift x·t→Y"), std::string::npos)
        << eff[0].ambiguous_with[0];
  }
  {
    const Problem pb = raster(
        [](const PointContext& pc) {
          return Eigen::Vector3d(0.0, 6.0 * pc.s.x() / 570.0 * (1.0 - std::exp(-pc.t / 200.0)),
                                 0.0);
        },
        false, 5);
    std::vector<SelectedTerm> eff{fitted(drift_with_x(200.0), {1.0})};
    mark_design_ambiguities(pb, offsets(), eff, {}, 4.0);
    EXPECT_TRUE(eff[0].ambiguous_with.empty()) << eff[0].ambiguous_with.front();
  }
}

// An effect is a function of a levelled axis only where it is one beside
// the datum too (DesignAmbiguityOptions::level_share_left_beside_datum).
// Two face diagonals of XY, five runs there and back on each (ISO 230-2's
// cycle), read along the line from an hour after the machine started: a
// uniform drift of X (τ 900 s) is by then mostly its mean, an offset of
// each line that the datum takes — and that a function of the 21 levels of
// x holds too, as two values per level fit the two lines. Judged on the
// raw column alone the drift was "a function of x" and so ambiguous with a
// cycle of X named beside it; beside the datum its course in time is all
// that is left, and none of it lies in the levels' span: the drift stays
// named. A scale of X
// is a function of the levels either way, and stays ambiguous with the
// cycle.
TEST(DiagnoseDesignAmbiguity, AnEffectIsAFunctionOfTheLevelsOnlyBesideTheDatum) {
  const Eigen::Vector3d lo(0.0, 0.0, 0.0), hi(400.0, 300.0, 0.0);
  const std::array<std::pair<Eigen::Vector3d, Eigen::Vector3d>, 2> lines{
      std::pair{lo, hi},
      std::pair{Eigen::Vector3d(400.0, 0.0, 0.0), Eigen::Vector3d(0.0, 300.0, 0.0)}};
  Problem pb;
  std::vector<double> y;
  std::mt19937_64 rng(12);
  std::normal_distribution<double> noise(0.0, 0.3);
  double t = 3600.0;
  for (const auto& [a, e] : lines)
    for (int run = 0; run < 5; ++run)
      for (const int way : {1, -1})
        for (int k = 0; k <= 20; ++k, t += 10.0) {
          const double f = way > 0 ? k / 20.0 : 1.0 - k / 20.0;
          const Eigen::Vector3d u = (e - a).normalized();
          PointContext pc;
          pc.p = pc.s = a + f * (e - a);
          pc.set = "a";
          pc.t = t;
          pc.dir = {way * u.x() > 0.0 ? 1 : -1, way * u.y() > 0.0 ? 1 : -1, 0};
          const double dx = 3.0 * (1.0 - std::exp(-t / 900.0));
          test::add_reading(pb, y, pc, u, u.x() * dx + noise(rng));
        }
  test::finish_problem(pb, y, "a", {true, true, false}, lo, hi);
  pb.var_lo[3] = 3600.0;
  pb.var_hi[3] = t;
  Term drift;
  drift.kind = TermKind::thermal_drift;
  drift.axis = drift.direction = 0;
  drift.tau_s = 900.0;
  for (const bool beside_datum : {true, false}) {
    DesignAmbiguityOptions o;
    o.level_share_left_beside_datum = beside_datum ? 0.5 : 1.0;
    o.cycle_period_test = false;
    std::vector<SelectedTerm> eff{fitted(drift, {3.0}), fitted(cyclic(0, 30.0), {0.2, 0.1})};
    const auto log = mark_design_ambiguities(pb, offsets(), eff, o, 4.0);
    if (beside_datum)
      EXPECT_TRUE(eff[0].ambiguous_with.empty()) << eff[0].ambiguous_with.front();
    else
      EXPECT_TRUE(std::find(eff[0].ambiguous_with.begin(), eff[0].ambiguous_with.end(),
                            "cyclic X→X (30.00 mm)") != eff[0].ambiguous_with.end())
          << fmt::format("{}", fmt::join(eff[0].ambiguous_with, " | "));
    std::vector<SelectedTerm> with_scale{fitted(scale(0), {3.0}),
                                         fitted(cyclic(0, 30.0), {0.2, 0.1})};
    mark_design_ambiguities(pb, offsets(), with_scale, o, 4.0);
    EXPECT_FALSE(with_scale[0].ambiguous_with.empty()) << beside_datum;
  }
}

}  // namespace
}  // namespace abbe::diagnose
