// The model table: names, `--model` lists, and a fourth model added by one
// register_model() call (the test-only "linear-only" model: Σ δ_j plus
// squareness, no angular terms) that the rest of the library then uses.
#include <gtest/gtest.h>

#include <random>

#include "abbe/io/input_error.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/model/model_kind.hpp"
#include "model_test_machines.hpp"

namespace abbe {
namespace {

using model::ModelKind;

model::Deviation linear_only(const model::ModelGeometry& geometry, const model::EvalPoint& point,
                             const Eigen::Vector3d& /*s*/, const model::ModelData& data) {
  model::Deviation d;
  for (const auto& err : data.errors) d.e_um += err.delta_um;
  d.e_um += geometry.squareness_um(point.p);
  return d;
}

ModelKind linear_only_kind() {
  static const ModelKind k = [] {
    model::ModelDescriptor d;
    d.name = "linear-only";
    d.column_suffix = "linear_only";
    d.description = "test: the linear errors alone";
    d.in_all = false;
    d.colour = "#000000";
    d.alternative = "htm";
    d.formula = &linear_only;
    return model::register_model(std::move(d));
  }();
  return k;
}

TEST(ModelTable, BuiltInRowsInOrder) {
  const auto& t = model::model_table();
  ASSERT_GE(t.size(), 3u);
  EXPECT_EQ(t[0]->name, "htm");
  EXPECT_EQ(t[1]->name, "ae-arm");
  EXPECT_EQ(t[2]->name, "dual");
  EXPECT_EQ(t[1]->column_suffix, "ae_arm");
  EXPECT_TRUE(t[2]->second_order);
  EXPECT_FALSE(t[0]->second_order);
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_EQ(static_cast<std::size_t>(t[i]->kind), i);
    EXPECT_EQ(model::parse_model_kind(t[i]->name), t[i]->kind);
    EXPECT_STREQ(model::to_string(t[i]->kind), t[i]->name.c_str());
  }
  EXPECT_EQ(model::alternative_model(ModelKind::htm), ModelKind::ae_arm);
  EXPECT_EQ(model::alternative_model(ModelKind::ae_arm), ModelKind::htm);
  EXPECT_EQ(model::alternative_model(ModelKind::dual), ModelKind::htm);
}

TEST(ModelTable, ParseModelList) {
  EXPECT_EQ(model::parse_model_list("all"),
            (std::vector<ModelKind>{ModelKind::htm, ModelKind::ae_arm, ModelKind::dual}));
  EXPECT_EQ(model::parse_model_list("dual"), std::vector<ModelKind>{ModelKind::dual});
  EXPECT_EQ(model::parse_model_list("dual,htm"),
            (std::vector<ModelKind>{ModelKind::dual, ModelKind::htm}));
  for (const char* bad : {"", "htm,", "ae_arm", "htm,htm", "HTM", "all,htm"}) {
    try {
      model::parse_model_list(bad);
      ADD_FAILURE() << "accepted \"" << bad << "\"";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().field, "--model") << bad;
    }
  }
  EXPECT_EQ(model::model_names_text(false).rfind("htm, ae-arm", 0), 0u);
}

TEST(ModelTable, RegisterRefusesTakenNamesAndMissingFormula) {
  model::ModelDescriptor d;
  d.name = "htm";
  d.formula = &linear_only;
  EXPECT_THROW(model::register_model(d), std::invalid_argument);
  d.name = "all";
  EXPECT_THROW(model::register_model(d), std::invalid_argument);
  d.name = "no-formula";
  d.formula = nullptr;
  EXPECT_THROW(model::register_model(d), std::invalid_argument);
}

// A fourth model is one formula plus one row: ErrorModel evaluates it, the
// names and lists know it, "all" leaves it out because its row says so.
TEST(ModelTable, FourthModelIsOneRow) {
  const ModelKind k = linear_only_kind();
  EXPECT_GE(static_cast<int>(k), 3);
  EXPECT_EQ(model::parse_model_kind("linear-only"), k);
  EXPECT_EQ(model::parse_model_list("ae-arm,linear-only"),
            (std::vector<ModelKind>{ModelKind::ae_arm, k}));
  EXPECT_EQ(model::parse_model_list("all").size(), 3u);
  const auto names = model::model_names(true);
  EXPECT_NE(std::find(names.begin(), names.end(), "linear-only"), names.end());
  EXPECT_EQ(names.back(), "all");
  EXPECT_EQ(model::descriptor(k).column_suffix, "linear_only");

  std::mt19937 rng(7);
  auto spec = test::spec_with("w Y' X' b Z t", test::random_table(rng, 3.0, 5.0));
  spec.squareness = {4.0, -2.0, 1.5};
  test::randomize_records(spec, rng);
  const machine::Machine m(std::move(spec));
  const model::ErrorModel linear(m, k);
  const model::ErrorModel ae_arm(m, ModelKind::ae_arm);
  EXPECT_EQ(linear.kind(), k);
  model::ModelData dl, da;
  for (int i = 0; i < 40; ++i) {
    const model::EvalPoint p = test::random_point(rng);
    const Eigen::Vector3d e = linear.evaluate(p, dl).e_um;
    ae_arm.evaluate(p, da);
    // Hand-computed: the sum of the looked-up linear errors plus squareness.
    const machine::Squareness& sq = m.squareness();
    Eigen::Vector3d expected(1e-3 * (-sq.ec0y * p.p.y() + sq.eb0z * p.p.z()),
                             1e-3 * (-sq.ea0z * p.p.z()), 0.0);
    for (const auto& err : da.errors) expected += err.delta_um;
    EXPECT_LT((e - expected).norm(), 1e-12) << i;
  }
  EXPECT_EQ(dl.evaluations, 40u);
}

}  // namespace
}  // namespace abbe
