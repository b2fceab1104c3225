#pragma once
// Residuals of the diagnosis: measured − predicted for every deviation
// component present in the measured data (or along the surface normal where
// only dn is given), one scalar observation each, plus the residual
// statistics of the three error models on the same data.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "abbe/diagnose/term.hpp"
#include "abbe/io/measured_data.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/model_kind.hpp"

namespace abbe::diagnose {

class Overlay;

// One scalar observation: y = u · (measured − predicted) at point `point`.
struct Observation {
  std::uint32_t point = 0;
  Eigen::Vector3d u = Eigen::Vector3d::UnitX();
};

struct ResidualStats {
  std::string model;
  double rms_um = 0.0;  // sqrt(Σ residual² / points): the RMS length of the residual vectors
  double max_um = 0.0;  // the largest residual vector length
};

struct Problem {
  std::string base_model;   // the model whose residual is diagnosed
  std::string other_model;  // the model model_choice compares with
  std::vector<PointContext> points;
  std::vector<std::size_t> lines;  // source line of each point (0: unknown)
  std::vector<Observation> obs;
  Eigen::VectorXd y;              // residual per observation, µm
  std::vector<std::string> sets;  // distinct `set` labels, in order of appearance
  std::array<bool, 3> direction_present{false, false, false};
  std::array<double, 4> var_lo{0, 0, 0, 0}, var_hi{0, 0, 0, 0};  // data range of s_x..s_z, t
  Eigen::Vector3d travel_mid = Eigen::Vector3d::Zero(), travel_half = Eigen::Vector3d::Ones();
  std::vector<ResidualStats> models;  // the models of `--model all`, in table order
};

// Builds the residual of `base` (plus `extend` when given) at every row.
Problem build_problem(const machine::Machine& machine, const io::MeasuredData& data,
                      model::ModelKind base, const Overlay* extend);

// RMS and max of residual vectors from per-observation residuals.
ResidualStats residual_stats(const Problem& problem, const Eigen::VectorXd& r);

}  // namespace abbe::diagnose
