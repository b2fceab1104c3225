// What the effects of a diagnosis explain, and how sure it is of them:
// unique + shared parts of each effect add up to what the effects explain
// together (two correlated terms share a large part, which the old unique
// shares left out); each effect's value has its standard uncertainty; an
// effect whose uncertainty exceeds its value is not named; gross outliers
// are flagged and left out (outliers.hpp).
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "abbe/diagnose/diagnosis.hpp"
#include "abbe/diagnose/outliers.hpp"
#include "abbe/diagnose/selection.hpp"

namespace abbe::diagnose {
namespace {

// A term of `kind` driven by and acting along axis `axis` (a datum offset
// of `set` for setup_offset).
Term term(TermKind kind, int axis, const std::string& set = "") {
  Term t;
  t.kind = kind;
  t.axis = t.direction = axis;
  t.set = set;
  return t;
}

// A run along X measured in dx, with the time growing along the run (t
// correlated with x): a scale X→X (a ppm) and a linear drift t→X (b µm/h).
Problem run(double a_ppm, double b_um_per_h, double sigma, std::uint64_t seed) {
  Problem pb;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<double> y;
  for (int i = 0; i < 600; ++i) {
    PointContext pc;
    pc.p = Eigen::Vector3d(-800.0 + 700.0 * (i % 300) / 299.0, -200.0, -150.0);
    pc.s = pc.p;
    // The clock: mostly along the run, plus a jitter that lets the two terms differ.
    pc.t = 12.0 * (i % 300) + 1800.0 * std::abs(n(rng));
    pc.dir = {1, 0, 0};
    pc.set = "run";
    pb.points.push_back(pc);
    pb.lines.push_back(static_cast<std::size_t>(i + 2));
    pb.obs.push_back({static_cast<std::uint32_t>(i), Eigen::Vector3d::UnitX()});
    y.push_back(7.0 + 1e-3 * a_ppm * pc.s.x() + b_um_per_h * pc.t / 3600.0 + sigma * n(rng));
  }
  pb.y = Eigen::Map<Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size()));
  pb.sets = {"run"};
  pb.direction_present = {true, false, false};
  pb.var_lo = {-800.0, -200.0, -150.0, 0.0};
  pb.var_hi = {-100.0, -200.0, -150.0, 12.0 * 299 + 1800.0 * 4};
  return pb;
}

CandidateSet two_terms() {
  CandidateSet cs;
  cs.datum.push_back(term(TermKind::setup_offset, 0, "run"));
  Term drift;
  drift.kind = TermKind::thermal_drift;
  drift.direction = 0;
  drift.axis = 0;
  drift.tau_s = 0.0;  // linear in t
  cs.fixed = {term(TermKind::scale, 0), drift};
  cs.named_tests = 2;
  return cs;
}

double corr(const Problem& pb, const CandidateSet& cs) {
  const Eigen::VectorXd a = term_columns(pb, cs.fixed[0]).col(0);
  const Eigen::VectorXd b = term_columns(pb, cs.fixed[1]).col(0);
  const Eigen::VectorXd ac = a.array() - a.mean(), bc = b.array() - b.mean();
  return ac.dot(bc) / (ac.norm() * bc.norm());
}

TEST(DiagnoseAttribution, UniqueAndSharedAddUpToTheTotal) {
  const Problem pb = run(12.0, 3.0, 0.5, 3);
  const CandidateSet cs = two_terms();
  EXPECT_GT(corr(pb, cs), 0.5);  // correlated terms: a large shared part
  const SelectionResult res = select_effects(pb, cs, SelectionOptions{});
  ASSERT_EQ(res.terms.size(), 2u);
  const double together = 1.0 - res.residual.squaredNorm() / res.datum_sse;
  double sum = 0.0, unique = 0.0;
  for (const SelectedTerm& st : res.terms) {
    EXPECT_NEAR(st.unique_fraction + st.shared_fraction, st.explained_fraction, 1e-12);
    EXPECT_GT(st.shared_fraction, 0.0);
    sum += st.explained_fraction;
    unique += st.unique_fraction;
  }
  EXPECT_NEAR(sum, together, 1e-9);
  EXPECT_NEAR(res.explained_together, together, 1e-9);
  // The unique shares alone fall well short of the total (the old report).
  EXPECT_LT(unique, 0.8 * together);
  EXPECT_GT(together, 0.9);
}

// Opposite signs on correlated terms (a suppression): each removes more
// given the other than alone, the shared part is negative, and the parts
// still add up to the total.
TEST(DiagnoseAttribution, SuppressionHasANegativeSharedPart) {
  const Problem pb = run(-12.0, 3.0, 0.5, 3);
  const SelectionResult res = select_effects(pb, two_terms(), SelectionOptions{});
  ASSERT_EQ(res.terms.size(), 2u);
  double sum = 0.0;
  for (const SelectedTerm& st : res.terms) {
    EXPECT_LT(st.shared_fraction, 0.0);
    EXPECT_NEAR(st.unique_fraction + st.shared_fraction, st.explained_fraction, 1e-12);
    sum += st.explained_fraction;
  }
  EXPECT_NEAR(sum, 1.0 - res.residual.squaredNorm() / res.datum_sse, 1e-9);
}

TEST(DiagnoseAttribution, IndependentTermsShareNothing) {
  // Two directions of one point: a scale X→X in dx and a reversal in dy
  // (orthogonal columns): shared ≈ 0, unique = explained.
  Problem pb;
  std::mt19937_64 rng(4);
  std::normal_distribution<double> n(0.0, 0.3);
  std::vector<double> y;
  for (int i = 0; i < 400; ++i) {
    PointContext pc;
    pc.p = Eigen::Vector3d(-800.0 + 2.0 * i, -100.0 - 0.5 * (i % 50), -150.0);
    pc.s = pc.p;
    pc.dir = {1, i % 2 ? 1 : -1, 0};
    pc.set = "a";
    pb.points.push_back(pc);
    pb.obs.push_back({static_cast<std::uint32_t>(i), Eigen::Vector3d::UnitX()});
    y.push_back(1e-3 * 20.0 * pc.s.x() + n(rng));
    pb.obs.push_back({static_cast<std::uint32_t>(i), Eigen::Vector3d::UnitY()});
    y.push_back(2.0 * pc.dir[1] + n(rng));
  }
  pb.y = Eigen::Map<Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size()));
  pb.sets = {"a"};
  pb.direction_present = {true, true, false};
  CandidateSet cs;
  for (int d = 0; d < 2; ++d) cs.datum.push_back(term(TermKind::setup_offset, d, "a"));
  cs.fixed = {term(TermKind::scale, 0), term(TermKind::reversal, 1)};
  cs.named_tests = 2;
  const SelectionResult res = select_effects(pb, cs, SelectionOptions{});
  ASSERT_EQ(res.terms.size(), 2u);
  double sum = 0.0;
  for (const SelectedTerm& st : res.terms) {
    EXPECT_NEAR(st.shared_fraction, 0.0, 1e-3);
    sum += st.explained_fraction;
  }
  EXPECT_NEAR(sum, 1.0 - res.residual.squaredNorm() / res.datum_sse, 1e-9);
}

TEST(DiagnoseUncertainty, ValueWithItsUncertaintyInTheReports) {
  const Problem pb = run(-12.0, 3.0, 0.5, 5);
  DiagnoseOptions o;
  const Diagnosis d = diagnose_problem(pb, o);
  ASSERT_FALSE(d.effects.empty());
  const std::string text = report_text(d);
  EXPECT_NE(text.find("value ± u"), std::string::npos) << text;
  EXPECT_NE(text.find("unique"), std::string::npos);
  for (const SelectedTerm& st : d.effects) {
    ASSERT_FALSE(st.term.stderr_.empty());
    EXPECT_GT(st.term.stderr_[0], 0.0);
    EXPECT_NE(text.find(effect_value_text(st.term)), std::string::npos) << text;
  }
  const std::string json = report_json(d);
  EXPECT_NE(json.find("\"unique_fraction\""), std::string::npos);
  EXPECT_NE(json.find("\"explained_together\""), std::string::npos);
}

TEST(DiagnoseUncertainty, AnEffectWhoseUncertaintyExceedsItsValueIsNotNamed) {
  Term t;
  t.kind = TermKind::scale;
  t.axis = t.direction = 0;
  t.coef = {2.0};
  t.stderr_ = {0.5};
  EXPECT_TRUE(value_significant(t));
  EXPECT_EQ(effect_value_text(t), "+2 ± 0.5 ppm");
  t.stderr_ = {2.5};
  EXPECT_FALSE(value_significant(t));
  t.coef = {-3.0};
  EXPECT_TRUE(value_significant(t));  // the magnitude counts, not the sign
  // A cyclic term: its amplitude against the amplitude's uncertainty.
  Term c;
  c.kind = TermKind::cyclic;
  c.axis = c.direction = 1;
  c.period_mm = 16.0;
  c.coef = {0.3, 0.4};  // amplitude 0.5
  c.stderr_ = {0.9, 0.9};
  EXPECT_FALSE(value_significant(c));
  c.stderr_ = {0.1, 0.1};
  EXPECT_TRUE(value_significant(c));

  // In the reports: not a name.
  Diagnosis d;
  d.model = "ae-arm";
  SelectedTerm st;
  st.term = t;
  st.term.coef = {1.0};
  st.term.stderr_ = {3.0};
  st.significant = value_significant(st.term);
  d.effects.push_back(st);
  EXPECT_NE(report_text(d).find("NOT SIGNIFICANT"), std::string::npos);
  EXPECT_NE(report_json(d).find("\"not_significant\""), std::string::npos);
}

TEST(DiagnoseOutliers, FlaggedLeftOutAndListed) {
  Problem pb = run(-12.0, 0.0, 0.5, 8);
  // 2 % of the points 20–50 µm off.
  std::mt19937_64 rng(9);
  std::set<std::size_t> bad;
  while (bad.size() < 12) bad.insert(static_cast<std::size_t>(rng() % pb.points.size()));
  int k = 0;
  for (std::size_t p : bad) {
    ++k;
    pb.y[static_cast<Eigen::Index>(p)] += (k % 2 ? -1.0 : 1.0) * (20.0 + 2.5 * k);
  }
  DiagnoseOptions o;
  const Diagnosis d = diagnose_problem(pb, o);
  ASSERT_EQ(d.outliers.size(), bad.size());
  for (const Outlier& out : d.outliers) {
    EXPECT_TRUE(bad.count(out.point));
    EXPECT_EQ(out.line, out.point + 2);
    EXPECT_GT(std::abs(out.residual_um), 19.0);
  }
  EXPECT_EQ(d.n_points, pb.points.size() - bad.size());
  EXPECT_NEAR(d.noise_um, 0.5, 0.1);
  // The scale is found as without the outliers.
  ASSERT_FALSE(d.effects.empty());
  EXPECT_EQ(d.effects[0].term.kind, TermKind::scale);
  EXPECT_NEAR(d.effects[0].term.coef[0], -12.0, 0.5);
  const std::string text = report_text(d);
  EXPECT_NE(text.find("outliers: 12 points"), std::string::npos) << text;
  EXPECT_NE(text.find("line "), std::string::npos);
  EXPECT_NE(report_json(d).find("\"outliers\""), std::string::npos);
  // Off: nothing flagged, the noise inflated.
  o.outliers.enabled = false;
  const Diagnosis raw = diagnose_problem(pb, o);
  EXPECT_TRUE(raw.outliers.empty());
  EXPECT_GT(raw.noise_um, 1.5);
}

TEST(DiagnoseOutliers, RobustSigmaAndRemoval) {
  EXPECT_EQ(robust_sigma(Eigen::VectorXd()), 0.0);
  Eigen::VectorXd r(5);
  r << 1.0, -1.0, 1.0, -1.0, 100.0;
  EXPECT_NEAR(robust_sigma(r), 1.482602218505602, 1e-12);
  const Problem pb = run(0.0, 0.0, 0.5, 2);
  const Problem cut = without_points(pb, {0, 5, 599});
  EXPECT_EQ(cut.points.size(), 597u);
  EXPECT_EQ(cut.obs.size(), 597u);
  EXPECT_EQ(cut.y[0], pb.y[1]);
  EXPECT_EQ(cut.lines[4], pb.lines[6]);
  EXPECT_EQ(cut.obs[4].point, 4u);
}

}  // namespace
}  // namespace abbe::diagnose
