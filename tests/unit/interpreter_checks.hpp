#pragma once
// Test helpers for the interpreter tests that run lines with run_lines
// (test_blocks.hpp): a point within a tolerance, and the error text of lines.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "abbe/io/input_error.hpp"
#include "test_blocks.hpp"

namespace abbe::gcode::testing {

// `actual` lies within `tol` (mm) of `expected`.
inline void expect_near(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected,
                        double tol = 1e-9) {
  EXPECT_NEAR((actual - expected).norm(), 0.0, tol)
      << "actual " << actual.transpose() << " expected " << expected.transpose();
}

// The error text the interpreter gives for `lines`, "" when it accepts them.
inline std::string error_of(const std::vector<std::string>& lines,
                            const InterpreterConfig& config = {}) {
  try {
    run_lines(lines, config);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace abbe::gcode::testing
