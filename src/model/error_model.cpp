#include "abbe/model/error_model.hpp"

#include <fmt/format.h>

#include "abbe/io/input_error.hpp"
#include "abbe/model/error_extension.hpp"
#include "ae_arm_model_inl.hpp"

namespace abbe::model {

using machine::Axis;

ErrorModel::ErrorModel(const machine::Machine& machine, ModelKind kind)
    : kind_(kind),
      formula_(descriptor(kind).formula),
      policy_(machine.out_of_range()),
      geometry_(std::make_shared<const ModelGeometry>(machine)) {
  auto tables = std::make_shared<Tables>();
  tables->file = machine.spec().table_file;
  for (Axis a : machine::kAxes) {
    auto ai = static_cast<std::size_t>(machine::index(a));
    for (int dir = -1; dir <= 1; ++dir)
      tables->by_axis_dir[ai][static_cast<std::size_t>(dir + 1)] =
          AxisErrorTable::build(machine.table(), a, dir, policy_);
  }
  tables_ = std::move(tables);
}

namespace {
// Out of line, so that lookup_at() stays small enough to be inlined into evaluate().
[[noreturn]] [[gnu::cold]] [[gnu::noinline]] void throw_out_of_range(const std::string& file, int j,
                                                                     double s, double lo,
                                                                     double hi) {
  throw InputError({file, 0, 0, std::string(1, "XYZ"[j]), ""},
                   fmt::format("axis {} position s = {:.4f} mm is outside the measured range "
                               "[{}, {}] mm of the component table (out_of_range: error)",
                               "XYZ"[j], s, lo, hi));
}
}  // namespace

void ErrorModel::lookup(const EvalPoint& point, ModelData& data) const {
  lookup_at(point.p + Eigen::Vector3d(0.0, 0.0, point.tool_length), point.dir, data);
}

void ErrorModel::lookup_at(const Eigen::Vector3d& s, const std::array<std::int8_t, 3>& dirs,
                           ModelData& data) const {
  for (std::size_t j = 0; j < 3; ++j) {
    int dir = dirs[j] > 0 ? 2 : dirs[j] < 0 ? 0 : 1;
    const AxisErrorTable& t = tables_->by_axis_dir[j][static_cast<std::size_t>(dir)];
    const double s_j = s[static_cast<Eigen::Index>(j)];
    if (!t.eval(s_j, data.errors[j])) {
      if (policy_ == machine::OutOfRangePolicy::error)
        throw_out_of_range(tables_->file, static_cast<int>(j), s_j, t.lo(), t.hi());
      ++data.out_of_range_lookups;
    }
  }
}

Deviation ErrorModel::evaluate(const EvalPoint& point, ModelData& data) const {
  const Eigen::Vector3d s = point.p + Eigen::Vector3d(0.0, 0.0, point.tool_length);
  lookup_at(s, point.dir, data);
  ++data.evaluations;
  // ae-arm, the default, inlined; every other model through its table row.
  Deviation d = kind_ == ModelKind::ae_arm ? evaluate_ae_arm_inline(*geometry_, point, s, data)
                                           : formula_(*geometry_, point, s, data);
  if (extension_) d.e_um += extension_->extra_um(point, d, data);
  return d;
}

ErrorModel ErrorModel::with_extension(std::shared_ptr<const ErrorExtension> extension) const {
  ErrorModel m = *this;
  m.extension_ = std::move(extension);
  return m;
}

ErrorModel ErrorModel::as_kind(ModelKind kind) const {
  ErrorModel m = *this;
  m.kind_ = kind;
  m.formula_ = descriptor(kind).formula;
  return m;
}

Eigen::Vector3d ErrorModel::measurement_point(Axis j, int k, const EvalPoint& point) const {
  return geometry_->measurement_point(j, k, point.p + Eigen::Vector3d(0.0, 0.0, point.tool_length));
}

Eigen::Vector3d ErrorModel::frame_origin(Axis j, const EvalPoint& point) const {
  return geometry_->frame_origin(j, point.p + Eigen::Vector3d(0.0, 0.0, point.tool_length));
}

}  // namespace abbe::model
