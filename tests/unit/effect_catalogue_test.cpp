// The effect catalogue: built-in rows, lookups, registration refusals, and a
// test-only effect kind that goes through Term, the overlay writer and reader
// and the report strings without any other code knowing it.
#include "abbe/diagnose/effect_catalogue.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "abbe/diagnose/overlay.hpp"
#include "abbe/io/input_error.hpp"

namespace abbe::diagnose {
namespace {

TEST(EffectCatalogue, BuiltInRows) {
  const auto& rows = effect_catalogue();
  ASSERT_GE(rows.size(), 11u);
  const char* names[] = {"model_choice",  "scale",          "squareness", "reversal",
                         "thermal_drift", "cyclic",         "coupling",   "arm_offset",
                         "setup_offset",  "setup_rotation", "unexplained"};
  for (std::size_t i = 0; i < 11; ++i) {
    EXPECT_EQ(static_cast<std::size_t>(rows[i].kind), i);
    EXPECT_EQ(rows[i].term_name, names[i]);
    EXPECT_EQ(find_effect(names[i]), &rows[i]);
  }
  EXPECT_STREQ(kind_id(TermKind::setup_offset), "setup");
  EXPECT_STREQ(kind_id(TermKind::setup_rotation), "setup");
  EXPECT_STREQ(term_name(TermKind::setup_rotation), "setup_rotation");
  EXPECT_EQ(find_effect("setup"), nullptr);
  EXPECT_EQ(find_effect("nonsense"), nullptr);

  Term cyc;
  cyc.kind = TermKind::cyclic;
  EXPECT_EQ(cyc.columns(), 2);
  Term smooth;
  smooth.kind = TermKind::unexplained;
  smooth.vars = {0, 3};
  smooth.degree = 2;
  EXPECT_EQ(smooth.columns(), 8);  // 3² multi-indices without the constant
  Term scale;
  scale.kind = TermKind::scale;
  EXPECT_EQ(scale.columns(), 1);
}

TEST(EffectCatalogue, UnknownKindThrows) {
  EXPECT_THROW(effect_descriptor(static_cast<TermKind>(4242)), std::invalid_argument);
}

TEST(EffectCatalogue, RegisterRefusesTakenKindNameAndMissingFormulas) {
  EffectDescriptor d = effect_descriptor(TermKind::scale);
  EXPECT_THROW(register_effect(d), std::invalid_argument);  // built-in value
  d.kind = static_cast<TermKind>(kFirstRegisteredKind + 50);
  EXPECT_THROW(register_effect(d), std::invalid_argument);  // name "scale" is taken
  d.term_name = "scale_again";
  d.basis = nullptr;
  EXPECT_THROW(register_effect(d), std::invalid_argument);  // no basis
}

// A test-only kind: a constant offset along `direction` for the points whose
// time is past `tau_s` (a step), one column.
EffectDescriptor step_effect() {
  EffectDescriptor d;
  d.kind = static_cast<TermKind>(kFirstRegisteredKind + 1);
  d.id = d.term_name = "test_step";
  d.reads_axis = d.writes_axis = false;
  d.basis = [](const Term& t, const PointContext& pc, BasisOut out) {
    if (pc.t >= t.tau_s) out(t.direction, 0) = 1.0;
  };
  d.label = [](const Term& t) { return fmt::format("step {}", axis_name(t.direction)); };
  d.description = [](const Term& t) {
    return fmt::format("{} steps by {:+.2f} µm at {:.0f} s", axis_name(t.direction),
                       t.coef.empty() ? 0.0 : t.coef[0], t.tau_s);
  };
  d.params = [](const Term& t) -> NamedValues {
    return {{"um", t.coef.empty() ? 0.0 : t.coef[0]}, {"at_s", t.tau_s}};
  };
  d.read_fields = [](Term& t, const OverlayFields& in) {
    t.tau_s = in.number("at_s");
    if (t.tau_s < 0.0) in.fail("at_s", "the step time must be ≥ 0");
  };
  d.write_fields = [](const Term& t, std::string& y) {
    y += fmt::format("    at_s: {:.17g}\n", t.tau_s);
  };
  return d;
}

TEST(EffectCatalogue, TestOnlyKindWorksEndToEnd) {
  if (!find_effect("test_step")) register_effect(step_effect());
  Term t;
  t.kind = static_cast<TermKind>(kFirstRegisteredKind + 1);
  t.direction = 2;
  t.tau_s = 60.0;
  t.coef = {3.5};
  t.stderr_ = {0.25};

  PointContext before, after;
  before.t = 10.0;
  after.t = 100.0;
  EXPECT_EQ(t.evaluate(before), Eigen::Vector3d::Zero());
  EXPECT_EQ(t.evaluate(after), Eigen::Vector3d(0.0, 0.0, 3.5));
  EXPECT_EQ(t.label(), "step Z");
  EXPECT_EQ(t.description(), "Z steps by +3.50 µm at 60 s");
  ASSERT_EQ(t.param_stderr().size(), 1u);  // the default: the first parameter's
  EXPECT_EQ(t.param_stderr()[0].first, "um");
  EXPECT_EQ(t.param_stderr()[0].second, 0.25);

  Overlay ov;
  ov.base_model = "ae-arm";
  ov.machine = "test";
  ov.terms.push_back(t);
  const std::string yaml = ov.to_yaml();
  EXPECT_NE(yaml.find("term: test_step"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("at_s: 60"), std::string::npos) << yaml;
  EXPECT_EQ(yaml.find("axis:"), std::string::npos) << yaml;
  const Overlay back = Overlay::parse(yaml, "step.yaml");
  ASSERT_EQ(back.terms.size(), 1u);
  EXPECT_EQ(back.terms[0].kind, t.kind);
  EXPECT_EQ(back.terms[0].direction, 2);
  EXPECT_EQ(back.terms[0].tau_s, 60.0);
  EXPECT_EQ(back.terms[0].coef, t.coef);
  EXPECT_EQ(back.to_yaml(), yaml);
  EXPECT_EQ(back.evaluate(after), Eigen::Vector3d(0.0, 0.0, 3.5));

  // The kind's own field errors name the file, the line and the key.
  std::string bad = yaml;
  bad.replace(bad.find("at_s: 60"), 8, "at_s: -1");
  try {
    Overlay::parse(bad, "step.yaml");
    FAIL() << "a negative step time was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "step.yaml");
    EXPECT_EQ(e.where().field, "at_s");
    EXPECT_GT(e.where().line, 0u);
    EXPECT_NE(std::string(e.what()).find("the step time must be ≥ 0"), std::string::npos);
  }
  std::string missing = yaml;
  missing.erase(missing.find("    at_s: 60\n"), 13);
  EXPECT_THROW(Overlay::parse(missing, "step.yaml"), InputError);
}

}  // namespace
}  // namespace abbe::diagnose
