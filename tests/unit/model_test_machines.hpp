#pragma once
// Small machines built in code for the machine and model tests.
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <random>
#include <string>
#include <vector>

#include "abbe/machine/machine.hpp"
#include "abbe/model/error_model.hpp"

namespace abbe::test {

// All 24 valid 3-axis chains: every order of X, Y, Z with `b` in every gap.
inline std::vector<std::string> all_chains() {
  std::vector<std::string> out;
  std::string axes = "XYZ";
  do {
    for (int bed = 0; bed <= 3; ++bed) {
      std::string c = "w";
      for (int i = 0; i < 3; ++i) {
        if (i == bed) c += " b";
        c += std::string(" ") + axes[static_cast<std::size_t>(i)];
        if (i < bed) c += "'";
      }
      if (bed == 3) c += " b";
      out.push_back(c + " t");
    }
  } while (std::next_permutation(axes.begin(), axes.end()));
  return out;
}

// A machine with the given chain and CSV table; every axis measured at
// `tip` with tool length `l_meas`, all reflectors at `point`.
inline machine::MachineSpec spec_with(const std::string& chain, const std::string& csv,
                                      const Eigen::Vector3d& tip = Eigen::Vector3d::Zero(),
                                      double l_meas = 100.0,
                                      const Eigen::Vector3d& point = Eigen::Vector3d::Zero()) {
  machine::MachineSpec spec;
  spec.name = "test";
  spec.file = "<test>";
  spec.chain = machine::KinematicChain::parse(chain);
  spec.travel = {machine::Travel{-1000, 0}, machine::Travel{-600, 0}, machine::Travel{-500, 0}};
  spec.tool_length = l_meas;
  for (auto& rec : spec.axes) {
    rec.present = true;
    rec.measured_tip = tip;
    rec.measured_tool_length = l_meas;
    rec.point = {point, point, point};
  }
  spec.table = machine::ComponentTable::parse(csv, "<test.csv>");
  return spec;
}

inline const char* kHeader = "axis,component,position_mm,direction,value\n";

// Rows of one constant component over a wide range.
inline std::string constant_rows(const std::string& component, double value,
                                 const std::string& dir = "mean") {
  std::string axis(1, component[2]);
  return fmt::format("{0},{1},-3000,{2},{3}\n{0},{1},3000,{2},{3}\n", axis, component, dir, value);
}

// A random table: every component of every axis, a few knots each,
// linear errors of `lin` µm and angular errors of `ang` µrad in size.
inline std::string random_table(std::mt19937& rng, double lin, double ang) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::string csv = kHeader;
  for (char a : {'X', 'Y', 'Z'})
    for (char d : {'X', 'Y', 'Z', 'A', 'B', 'C'}) {
      double amp = (d == 'A' || d == 'B' || d == 'C') ? ang : lin;
      for (int i = 0; i <= 6; ++i)
        csv +=
            fmt::format("{},E{}{},{},mean,{:.17g}\n", a, d, a, -1200.0 + 400.0 * i, amp * u(rng));
    }
  return csv;
}

// Random reflector points and measurement positions.
inline void randomize_records(machine::MachineSpec& spec, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-900.0, 0.0);
  std::uniform_real_distribution<double> l(50.0, 250.0);
  for (auto& rec : spec.axes) {
    rec.measured_tip = {u(rng), u(rng) * 0.6, u(rng) * 0.5};
    rec.measured_tool_length = l(rng);
    for (auto& p : rec.point) p = {u(rng), u(rng) * 0.6, u(rng) * 0.5};
  }
}

inline model::EvalPoint random_point(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1000.0, 0.0);
  std::uniform_real_distribution<double> l(50.0, 250.0);
  std::uniform_int_distribution<int> d(-1, 1);
  model::EvalPoint p;
  p.p = {u(rng), u(rng) * 0.6, u(rng) * 0.5 - 100.0};
  p.tool_length = l(rng);
  p.dir = {static_cast<std::int8_t>(d(rng)), static_cast<std::int8_t>(d(rng)),
           static_cast<std::int8_t>(d(rng))};
  return p;
}

}  // namespace abbe::test
