#pragma once
// Part alignment: the rigid motion with which a part is set up and inspected
// (as CMM software aligns a measured part to its nominal geometry), applied
// to a predicted toolpath so that the deviation left after the set-up can be
// reported beside the absolute one (docs/models.md, "The part").
//
// best_fit: the least-squares rigid motion T (rotation and translation, exact,
// not linearised; Kabsch's SVD solution) minimising Σ|T(P'_i) − P_i|² over the
// given points, P_i nominal, P'_i = P_i + e_i predicted.
//
// datums (3-2-1): a primary point set fixes a plane (two rotations and the
// translation along its normal), a secondary set a line in that plane (the
// rotation about the normal and the translation across the line), a tertiary
// set a point (the translation along the line). Each feature is fitted by least
// squares to the nominal and to the predicted points; T makes the predicted
// features coincide with the nominal ones.
#include <Eigen/Core>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace abbe::pipeline {

// x ↦ rotation·x + translation (mm).
struct RigidMotion {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation_mm = Eigen::Vector3d::Zero();

  Eigen::Vector3d apply(const Eigen::Vector3d& x) const { return rotation * x + translation_mm; }
  // this ∘ first: x ↦ this(first(x)).
  RigidMotion after(const RigidMotion& first) const;
  // The rotation as a rotation vector (axis · angle), µrad.
  Eigen::Vector3d rotation_urad() const;
};

// Nominal points (mm) and their predicted deviations (µm), index for index.
struct PartPoints {
  std::vector<Eigen::Vector3d> nominal_mm;
  std::vector<Eigen::Vector3d> deviation_um;
  std::size_t size() const { return nominal_mm.size(); }
  void add(const Eigen::Vector3d& p_mm, const Eigen::Vector3d& e_um) {
    nominal_mm.push_back(p_mm);
    deviation_um.push_back(e_um);
  }
};

// Why an alignment cannot be computed (too few points, collinear points, a
// datum set that does not define its feature). The message names the set.
class AlignmentError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The deviation that remains after aligning the predicted point P + e with
// `motion`: T(P + e) − P, µm.
Eigen::Vector3d aligned_deviation_um(const RigidMotion& motion, const Eigen::Vector3d& p_mm,
                                     const Eigen::Vector3d& e_um);

// Least-squares rigid fit of the predicted points to the nominal ones. Throws
// AlignmentError for fewer than three points or collinear nominal points (the
// rotation about the line would be undetermined).
RigidMotion best_fit(const PartPoints& points);

// 3-2-1 alignment; the sets index into `points`. Primary: at least three
// non-collinear points; secondary: at least two points whose projections
// onto the primary plane are distinct; tertiary: at least one point. Throws
// AlignmentError naming the set that does not define its feature.
struct DatumIndices {
  std::vector<std::size_t> primary, secondary, tertiary;
};
RigidMotion datum_alignment(const PartPoints& points, const DatumIndices& datums);

}  // namespace abbe::pipeline
