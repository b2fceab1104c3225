#pragma once
// ModelGeometry: what every model formula needs of the machine besides the
// component errors — the chain order, where each axis' errors act (the
// measurement points M_{j,k}(q) and the frame origins O_j(q)) and the
// squareness. Built once from a Machine, immutable, shared by ErrorModel.
#include <Eigen/Core>
#include <array>

#include "abbe/io/units.hpp"
#include "abbe/machine/machine.hpp"

namespace abbe::model {

class ModelGeometry {
 public:
  struct AxisGeometry {
    Eigen::Array3d moves;  // 1 for i ∈ U(j): the axes that carry axis j's frame
    // M_{j,k}(q) = m0_k + moves∘s (column k): m0_k = M_meas_k − moves∘s_meas.
    Eigen::Matrix3d m0;
  };

  explicit ModelGeometry(const machine::Machine& machine);

  // The chain order, workpiece to tool (w to t).
  const std::array<machine::Axis, 3>& order() const { return order_; }
  // By axis index (0 = X).
  const AxisGeometry& axis(std::size_t j) const { return axes_[j]; }
  const machine::Squareness& squareness() const { return squareness_; }

  // (−EC0Y·y + EB0Z·z, −EA0Z·z, 0) µrad × mm, in µm.
  Eigen::Vector3d squareness_um(const Eigen::Vector3d& p) const {
    return units::kUmPerUradMm *
           Eigen::Vector3d(-squareness_.ec0y * p.y() + squareness_.eb0z * p.z(),
                           -squareness_.ea0z * p.z(), 0.0);
  }
  // M_{j,k}(q) and O_j(q), mm, at axis positions s.
  Eigen::Vector3d measurement_point(machine::Axis j, int k, const Eigen::Vector3d& s) const;
  Eigen::Vector3d frame_origin(machine::Axis j, const Eigen::Vector3d& s) const;

 private:
  std::array<machine::Axis, 3> order_;
  std::array<AxisGeometry, 3> axes_;
  machine::Squareness squareness_;
};

}  // namespace abbe::model
