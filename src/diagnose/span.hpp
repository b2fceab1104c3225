#pragma once
// Column spans of the checks after the fit (design_ambiguity.cpp,
// rival_check.cpp): an orthonormal basis by two-pass Gram–Schmidt and the
// part of columns outside a span.
#include <Eigen/Core>

namespace abbe::diagnose::span {

// Orthonormal basis of the span of A's columns; a column already in the
// span of the ones before it (or zero) is dropped.
Eigen::MatrixXd orthonormal(const Eigen::MatrixXd& A);

// C minus its projection on the span of the orthonormal columns of Q.
Eigen::MatrixXd residual_of(const Eigen::MatrixXd& Q, const Eigen::MatrixXd& C);

}  // namespace abbe::diagnose::span
