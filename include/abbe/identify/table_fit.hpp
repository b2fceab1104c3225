#pragma once
// Piecewise-linear component tables fitted to volumetric data. Every
// component E<d><j> of every axis is a piecewise-linear function of s_j with
// knots every `knot_spacing_mm` over the range of s_j the data cover; its
// knot values are the unknowns. The first-order (ε) part of the D₂ chain is
// linear in them: a point contributes, per component, the chain's response to
// a unit error times the hat-function weight of each knot. The ε² part is
// left out of the fit (it is 10⁻⁴ of the first order at 10 µrad; see
// docs/identification.md).
//
// Not everything is separable from one volumetric grid with one tool length:
// an angular error whose arms are constant over the grid (every arm of the
// spindle axis Z; the arms along the axes that carry the carriage) acts like
// a straightness or positioning error, constant parts of all errors of one
// direction add up, and constant angular parts trade with straightness
// slopes. The null space of the design names these combinations per
// component; the fit then chooses the gauge that keeps angular errors
// smallest (their columns carry a weight of 10⁻³ in the minimum-norm choice),
// so what cannot be separated ends up in the linear components, and the
// prediction on the grid does not depend on the choice.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "abbe/identify/least_squares.hpp"
#include "abbe/identify/parameter_identification.hpp"
#include "abbe/machine/machine.hpp"

namespace abbe::identify {

struct TableFitOptions {
  double knot_spacing_mm = 50.0;
  LeastSquaresOptions least_squares;
};

struct FittedSeries {
  machine::ComponentId id;
  std::vector<double> knots_mm;  // axis positions s_j
  std::vector<double> value;     // µm or µrad
  std::vector<double> stderr_value;
};

struct ComponentSeparability {
  machine::ComponentId id;
  // The eigenvalues of the component's block of the null-space projector:
  // the largest (0 = separable, 1 = a shape of it the data cannot see) and
  // how many exceed 10⁻³ (shapes involved in an ambiguity), of `knots`.
  double null_share = 0.0;
  int null_dims = 0;
  int knots = 0;
  std::vector<std::string> confounded_with;  // components sharing those unseen shapes
};

struct TableFit {
  std::vector<FittedSeries> series;  // 18 components (axes with data)
  std::vector<ComponentSeparability> separability;
  LeastSquaresResult fit;  // the unweighted design: rank, condition, null space
  int unknowns = 0;
  double residual_rms_um = 0.0;
  double residual_max_um = 0.0;
  std::size_t n_values = 0;
  std::vector<std::string> unidentifiable;  // described null directions (component-level)
};

TableFit fit_component_tables(const ChainExpansion& chain, const std::vector<Observation>& data,
                              const TableFitOptions& options = {});

// Component table CSV (docs/formats.md): axis,component,position_mm,direction,value (mean).
std::string table_fit_to_csv(const TableFit& fit);

}  // namespace abbe::identify
