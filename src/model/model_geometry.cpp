#include "abbe/model/model_geometry.hpp"

namespace abbe::model {

ModelGeometry::ModelGeometry(const machine::Machine& machine)
    : order_(machine.chain().order()), squareness_(machine.squareness()) {
  for (machine::Axis a : machine::kAxes) {
    AxisGeometry& g = axes_[static_cast<std::size_t>(machine::index(a))];
    auto mask = machine.chain().moves_mask(a);
    g.moves = Eigen::Array3d(mask[0], mask[1], mask[2]);
    const machine::AxisRecord& rec = machine.record(a);
    Eigen::Array3d s_meas = rec.measured_axes().array();
    for (int k = 0; k < 3; ++k)
      g.m0.col(k) = (rec.point[static_cast<std::size_t>(k)].array() - g.moves * s_meas).matrix();
  }
}

Eigen::Vector3d ModelGeometry::measurement_point(machine::Axis j, int k,
                                                 const Eigen::Vector3d& s) const {
  const AxisGeometry& g = axes_[static_cast<std::size_t>(machine::index(j))];
  return g.m0.col(k) + (g.moves * s.array()).matrix();
}

Eigen::Vector3d ModelGeometry::frame_origin(machine::Axis j, const Eigen::Vector3d& s) const {
  const AxisGeometry& g = axes_[static_cast<std::size_t>(machine::index(j))];
  return (g.moves * s.array()).matrix();
}

}  // namespace abbe::model
