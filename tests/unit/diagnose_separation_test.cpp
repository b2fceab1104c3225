// What measurement would tell an ambiguous effect from its rivals
// (separation.hpp): aliased periods, time against position, different
// driving axes, and the general case.
#include <gtest/gtest.h>

#include "abbe/diagnose/separation.hpp"

namespace abbe::diagnose {
namespace {

Term term(TermKind kind, int axis, int direction) {
  Term t;
  t.kind = kind;
  t.axis = axis;
  t.direction = direction;
  return t;
}

TEST(DiagnoseSeparation, NothingToSeparateWithoutRivals) {
  EXPECT_EQ(separating_measurement(term(TermKind::scale, 0, 0), {}, {}), "");
}

TEST(DiagnoseSeparation, AliasedPeriodsAskForIrregularSpacingAlongTheAxis) {
  Term c = term(TermKind::cyclic, 1, 1);
  c.period_mm = 20.0;
  const std::string s = separating_measurement(c, {}, {100.0 / 3.0});
  EXPECT_NE(s.find("sample Y at irregular spacing"), std::string::npos) << s;
  EXPECT_NE(s.find("20, 33.3333 mm"), std::string::npos) << s;
}

TEST(DiagnoseSeparation, TimeAgainstPositionAsksForAnotherOrder) {
  // A drift of Z in time against a scale of Z: one pass up the grid moves
  // time and Z together (the demo's one-pass case).
  Term drift = term(TermKind::thermal_drift, -1, 2);
  const std::string s = separating_measurement(drift, {term(TermKind::scale, 2, 2)}, {});
  EXPECT_NE(s.find("another order or after a pause"), std::string::npos) << s;
  // Either way round.
  EXPECT_EQ(separating_measurement(term(TermKind::scale, 2, 2), {drift}, {}), s);
  // A smooth function of t counts as time-dependent; of x, y, z it does not.
  Term smooth_t = term(TermKind::unexplained, -1, 2);
  smooth_t.vars = {0, 3};
  EXPECT_EQ(separating_measurement(smooth_t, {term(TermKind::scale, 0, 2)}, {}), s);
}

TEST(DiagnoseSeparation, DifferentDrivingAxesAskForThemToVaryApart) {
  const std::string s =
      separating_measurement(term(TermKind::squareness, 0, 2), {term(TermKind::scale, 2, 2)}, {});
  EXPECT_NE(s.find("where X and Z vary apart"), std::string::npos) << s;
}

TEST(DiagnoseSeparation, SwappedSquarenessIsOneOutOfSquarenessOfAPlate) {
  // A plate's rotation is datum: d_X ∝ y and d_Y ∝ x fit it alike (the
  // real plates 1597A and 2130); not "X and Y vary apart".
  const std::string s = separating_measurement(term(TermKind::squareness, 1, 0),
                                               {term(TermKind::squareness, 0, 1)}, {});
  EXPECT_NE(s.find("dX ∝ y and dY ∝ x differ by a rotation about Z alone"), std::string::npos) << s;
  EXPECT_NE(s.find("one out-of-squareness of Y and X"), std::string::npos) << s;
  EXPECT_EQ(s.find("vary apart"), std::string::npos) << s;
  // Squareness against another squareness that is not its swap: as before.
  const std::string t = separating_measurement(term(TermKind::squareness, 1, 0),
                                               {term(TermKind::squareness, 2, 0)}, {});
  EXPECT_NE(t.find("vary apart"), std::string::npos) << t;
}

TEST(DiagnoseSeparation, OtherwiseTheGeneralAdvice) {
  // Same driving axis, no time: nothing specific can be said.
  const std::string s =
      separating_measurement(term(TermKind::scale, 0, 0), {term(TermKind::reversal, 0, 0)}, {});
  EXPECT_NE(s.find("where these explanations differ"), std::string::npos) << s;
}

}  // namespace
}  // namespace abbe::diagnose
