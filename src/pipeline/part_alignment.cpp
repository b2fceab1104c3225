#include "abbe/pipeline/part_alignment.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "abbe/io/units.hpp"

namespace abbe::pipeline {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// Points closer together than this (mm) do not define a direction.
constexpr double kSpreadMm = 1e-6;
// A set whose second principal extent is below this fraction of the first
// is taken as collinear.
constexpr double kCollinear = 1e-6;

Vector3d predicted(const PartPoints& pts, std::size_t i) {
  return pts.nominal_mm[i] + units::kMmPerUm * pts.deviation_um[i];
}

template <class Get>
Vector3d centroid(const std::vector<std::size_t>& idx, Get get) {
  Vector3d c = Vector3d::Zero();
  for (std::size_t i : idx) c += get(i);
  return c / static_cast<double>(idx.size());
}

// Principal extents (square roots of the covariance eigenvalues, ascending)
// and axes of the points about `c`, after removing the component along
// `drop` (zero: none).
template <class Get>
Eigen::SelfAdjointEigenSolver<Matrix3d> principal(const std::vector<std::size_t>& idx, Get get,
                                                  const Vector3d& c, const Vector3d& drop) {
  Matrix3d cov = Matrix3d::Zero();
  for (std::size_t i : idx) {
    Vector3d q = get(i) - c;
    q -= q.dot(drop) * drop;
    cov += q * q.transpose();
  }
  return Eigen::SelfAdjointEigenSolver<Matrix3d>(cov / static_cast<double>(idx.size()));
}

double extent(const Eigen::SelfAdjointEigenSolver<Matrix3d>& e, int k) {
  return std::sqrt(std::max(0.0, e.eigenvalues()(k)));
}

// The rotation taking unit vector a to unit vector b (a·b > 0), the smallest one.
Matrix3d rotation_between(const Vector3d& a, const Vector3d& b) {
  const Vector3d v = a.cross(b);
  const double c = a.dot(b);
  Matrix3d k;
  k << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return Matrix3d::Identity() + k + k * k / (1.0 + c);
}

// x ↦ r·(x − pivot) + pivot + shift.
RigidMotion about(const Matrix3d& r, const Vector3d& pivot, const Vector3d& shift) {
  RigidMotion m;
  m.rotation = r;
  m.translation_mm = pivot - r * pivot + shift;
  return m;
}

void check_indices(const PartPoints& pts, const std::vector<std::size_t>& idx, const char* name,
                   std::size_t minimum) {
  if (idx.size() < minimum)
    throw AlignmentError(std::string("the ") + name + " datum needs at least " +
                         std::to_string(minimum) + " point(s), it has " +
                         std::to_string(idx.size()));
  for (std::size_t i : idx)
    if (i >= pts.size()) throw AlignmentError(std::string("the ") + name + " datum: bad index");
}

}  // namespace

RigidMotion RigidMotion::after(const RigidMotion& first) const {
  RigidMotion m;
  m.rotation = rotation * first.rotation;
  m.translation_mm = rotation * first.translation_mm + translation_mm;
  return m;
}

Vector3d RigidMotion::rotation_urad() const {
  const Eigen::AngleAxisd aa(rotation);
  return aa.angle() * aa.axis() * 1e6;
}

Vector3d aligned_deviation_um(const RigidMotion& motion, const Vector3d& p_mm,
                              const Vector3d& e_um) {
  // T(P + e) − P = (R − I)·P + t + R·e, written so that no mm-sized term is
  // rounded before the µm-sized ones are added.
  const Vector3d moved = (motion.rotation - Matrix3d::Identity()) * p_mm + motion.translation_mm;
  return units::kUmPerMm * moved + motion.rotation * e_um;
}

RigidMotion best_fit(const PartPoints& pts) {
  const std::size_t n = pts.size();
  if (n < 3)
    throw AlignmentError("a best fit needs at least 3 points, the part has " + std::to_string(n));
  std::vector<std::size_t> all(n);
  for (std::size_t i = 0; i < n; ++i) all[i] = i;
  auto nominal = [&](std::size_t i) { return pts.nominal_mm[i]; };
  auto pred = [&](std::size_t i) { return predicted(pts, i); };
  const Vector3d c = centroid(all, nominal);
  const Vector3d cp = centroid(all, pred);
  const auto shape = principal(all, nominal, c, Vector3d::Zero());
  if (extent(shape, 2) < kSpreadMm || extent(shape, 1) < kCollinear * extent(shape, 2))
    throw AlignmentError(
        "the points of the part are collinear: a best fit cannot fix the rotation about their "
        "line");
  // Kabsch: H = Σ (P'_i − c')(P_i − c)ᵀ = U S Vᵀ, R = V diag(1, 1, det(V Uᵀ)) Uᵀ.
  Matrix3d h = Matrix3d::Zero();
  for (std::size_t i = 0; i < n; ++i) h += (pred(i) - cp) * (nominal(i) - c).transpose();
  const Eigen::JacobiSVD<Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Matrix3d d = Matrix3d::Identity();
  d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
  const Matrix3d r = svd.matrixV() * d * svd.matrixU().transpose();
  RigidMotion m;
  m.rotation = r;
  m.translation_mm = c - r * cp;
  return m;
}

RigidMotion datum_alignment(const PartPoints& pts, const DatumIndices& datums) {
  check_indices(pts, datums.primary, "primary", 3);
  check_indices(pts, datums.secondary, "secondary", 2);
  check_indices(pts, datums.tertiary, "tertiary", 1);
  auto nominal = [&](std::size_t i) { return pts.nominal_mm[i]; };

  // 3: the primary plane.
  const Vector3d ca = centroid(datums.primary, nominal);
  const auto plane = principal(datums.primary, nominal, ca, Vector3d::Zero());
  if (extent(plane, 2) < kSpreadMm || extent(plane, 1) < kCollinear * extent(plane, 2))
    throw AlignmentError("the primary datum's points are collinear: they do not define a plane");
  const Vector3d normal = plane.eigenvectors().col(0).normalized();
  auto pred0 = [&](std::size_t i) { return predicted(pts, i); };
  const Vector3d cpa = centroid(datums.primary, pred0);
  Vector3d normal_p =
      principal(datums.primary, pred0, cpa, Vector3d::Zero()).eigenvectors().col(0).normalized();
  if (normal_p.dot(normal) < 0) normal_p = -normal_p;
  const RigidMotion t1 =
      about(rotation_between(normal_p, normal), cpa, normal.dot(ca - cpa) * normal);

  // 2: the secondary line, in the primary plane.
  auto pred1 = [&](std::size_t i) { return t1.apply(predicted(pts, i)); };
  const Vector3d cb = centroid(datums.secondary, nominal);
  const auto line = principal(datums.secondary, nominal, cb, normal);
  if (extent(line, 2) < kSpreadMm)
    throw AlignmentError(
        "the secondary datum's points coincide in the primary plane: they do not define a line");
  const Vector3d dir = line.eigenvectors().col(2).normalized();
  const Vector3d cpb = centroid(datums.secondary, pred1);
  Vector3d dir_p = principal(datums.secondary, pred1, cpb, normal).eigenvectors().col(2);
  dir_p = (dir_p - dir_p.dot(normal) * normal).normalized();
  if (dir_p.dot(dir) < 0) dir_p = -dir_p;
  const double angle = std::atan2(normal.dot(dir_p.cross(dir)), dir_p.dot(dir));
  const Vector3d across = normal.cross(dir);
  const RigidMotion t2 = about(Eigen::AngleAxisd(angle, normal).toRotationMatrix(), cpb,
                               across.dot(cb - cpb) * across);
  const RigidMotion t21 = t2.after(t1);

  // 1: the tertiary point, along the line.
  auto pred2 = [&](std::size_t i) { return t21.apply(predicted(pts, i)); };
  const Vector3d cc = centroid(datums.tertiary, nominal);
  const Vector3d cpc = centroid(datums.tertiary, pred2);
  RigidMotion t3;
  t3.translation_mm = dir.dot(cc - cpc) * dir;
  return t3.after(t21);
}

}  // namespace abbe::pipeline
