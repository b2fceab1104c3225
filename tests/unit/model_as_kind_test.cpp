// ErrorModel::as_kind: a model built from another model of the same machine
// (sharing its geometry and resampled tables, as ModelSet builds `--model
// all`) evaluates exactly as the model built from the machine, with and
// without an overlay-like extension; and ModelSet's deviations are those of
// the models built one by one.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"
#include "abbe/model/model_kind.hpp"
#include "abbe/pipeline/model_set.hpp"

namespace abbe::model {
namespace {

const std::string kMachine = std::string(ABBE_SOURCE_DIR) + "/machines/sample/machine.yaml";

std::vector<EvalPoint> points() {
  std::vector<EvalPoint> out;
  for (int i = 0; i < 40; ++i) {
    EvalPoint p;
    p.p = Eigen::Vector3d(-20.0 - 23.0 * i, -10.0 - 11.5 * i, -30.0 - 9.0 * (i % 17));
    p.tool_length = 100.0 + 2.0 * (i % 5);
    p.dir = {static_cast<std::int8_t>(i % 2 ? 1 : -1), static_cast<std::int8_t>(i % 3 ? 1 : -1), 1};
    out.push_back(p);
  }
  return out;
}

TEST(ModelAsKind, EvaluatesAsTheModelBuiltFromTheMachine) {
  const machine::Machine m = machine::Machine::load(kMachine);
  const std::vector<ModelKind> kinds = {ModelKind::htm, ModelKind::ae_arm, ModelKind::dual};
  for (ModelKind first : kinds)
    for (ModelKind k : kinds) {
      const ErrorModel direct(m, k);
      const ErrorModel shared = ErrorModel(m, first).as_kind(k);
      EXPECT_EQ(shared.kind(), k);
      ModelData a, b;
      for (const EvalPoint& p : points()) {
        const Deviation da = direct.evaluate(p, a), db = shared.evaluate(p, b);
        EXPECT_EQ(da.e_um, db.e_um);
        EXPECT_EQ(da.second_order_um, db.second_order_um);
      }
    }
}

TEST(ModelAsKind, ModelSetGivesTheDeviationsOfSeparateModels) {
  const machine::Machine m = machine::Machine::load(kMachine);
  const std::vector<ModelKind> kinds = {ModelKind::htm, ModelKind::ae_arm, ModelKind::dual};
  pipeline::ModelSet set(m, kinds);
  std::vector<ErrorModel> separate;
  std::vector<ModelData> data(kinds.size());
  for (ModelKind k : kinds) separate.emplace_back(m, k);
  for (const EvalPoint& p : points()) {
    set.evaluate(p, "points.csv", 1);
    for (std::size_t i = 0; i < kinds.size(); ++i) {
      EXPECT_EQ(set.deviations()[i].e_um, separate[i].evaluate(p, data[i]).e_um);
      EXPECT_GT(set.norms_um()[i], 0.0);
    }
  }
}

}  // namespace
}  // namespace abbe::model
