#pragma once
// ErrorModel / ModelData: the Model/Data pair of the error prediction.
// ErrorModel is immutable and built once from a Machine (tables resampled per
// axis and direction, measurement points and U(j) folded into constants);
// ModelData is the per-thread workspace of the evaluations (the component
// errors looked up last, out-of-range counter). evaluate() predicts the
// deviation of the tool tip from its nominal position at one point
// (docs/models.md).
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>

#include "abbe/machine/machine.hpp"
#include "abbe/model/axis_error_table.hpp"
#include "abbe/model/model_geometry.hpp"
#include "abbe/model/model_kind.hpp"

namespace abbe::model {

class ErrorExtension;  // error_extension.hpp

// What the models evaluate: a PathPoint or a row of measured data.
struct EvalPoint {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();  // nominal tool tip P, machine coordinates, mm
  double tool_length = 0.0;                     // active L, mm (s = P + L·e_z)
  std::array<std::int8_t, 3> dir{0, 0, 0};      // sign of the last motion of each axis
  double time = 0.0;                            // s (unused by the v1 models)
};

struct Deviation {
  Eigen::Vector3d e_um =
      Eigen::Vector3d::Zero();  // predicted P' − P, µm (all orders the model has)
  // dual: the ε² part (included in e_um); zero for htm and ae-arm.
  Eigen::Vector3d second_order_um = Eigen::Vector3d::Zero();
};

class ModelData {
 public:
  std::size_t out_of_range_lookups = 0;  // (point, axis) lookups outside the measured range
  std::size_t evaluations = 0;
  std::array<AxisErrors, 3> errors;  // per axis, from the last evaluation
};

class ErrorModel {
 public:
  ErrorModel(const machine::Machine& machine, ModelKind kind);

  ModelKind kind() const { return kind_; }
  const ModelGeometry& geometry() const { return *geometry_; }
  machine::OutOfRangePolicy policy() const { return policy_; }

  // Throws abbe::InputError (field "X", "Y" or "Z") when the policy is
  // `error` and an axis position lies outside its measured range.
  // With an extension, its extra deviation is included in e_um.
  Deviation evaluate(const EvalPoint& point, ModelData& data) const;

  // A copy of this model whose evaluate() adds the extension's terms
  // (the extended model); nullptr removes it.
  ErrorModel with_extension(std::shared_ptr<const ErrorExtension> extension) const;
  const ErrorExtension* extension() const { return extension_.get(); }

  // The model `kind` of the same machine (and extension) as this one,
  // sharing its geometry and resampled tables, which do not depend on the
  // model: several models of one machine are built at the cost of one.
  ErrorModel as_kind(ModelKind kind) const;

  // The component errors of every axis at the point (also left in data.errors).
  void lookup(const EvalPoint& point, ModelData& data) const;

  // M_{j,k}(q) and O_j(q) (mm) at a point, for tests and reports.
  Eigen::Vector3d measurement_point(machine::Axis j, int k, const EvalPoint& point) const;
  Eigen::Vector3d frame_origin(machine::Axis j, const EvalPoint& point) const;

 private:
  struct Tables {
    std::array<std::array<AxisErrorTable, 3>, 3> by_axis_dir;  // [axis][0 rev,1 mean,2 fwd]
    std::string file;
  };

  // The lookup at axis positions s = P + L·e_z with the axes' directions of motion.
  void lookup_at(const Eigen::Vector3d& s, const std::array<std::int8_t, 3>& dirs,
                 ModelData& data) const;

  ModelKind kind_;
  ModelFormula formula_;  // the model table's row for kind_
  machine::OutOfRangePolicy policy_;
  std::shared_ptr<const ModelGeometry> geometry_;
  std::shared_ptr<const Tables> tables_;
  std::shared_ptr<const ErrorExtension> extension_;  // null: the plain model
};

}  // namespace abbe::model
