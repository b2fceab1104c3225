#pragma once
// Term: one candidate effect of the diagnosis as a set of basis functions of
// the measured point (DESIGN.md §5 kinds plus `unexplained` smooth
// functions). The residual model is Σ_terms Σ_c coef_c · g_c(point), each
// g_c a 3-vector deviation in µm per unit coefficient. The same Terms, with
// their fitted coefficients, form the machine overlay (overlay.hpp).
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace abbe::diagnose {

// The variables a smooth function (Term::vars) is built on: 0..2 the axis
// positions s_x, s_y, s_z, and this one the time.
constexpr int kTimeVariable = 3;

// What the basis functions need to know about one measured point.
struct PointContext {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();  // tool tip P, mm
  Eigen::Vector3d s = Eigen::Vector3d::Zero();  // axis positions s = P + L·e_z, mm
  double t = 0.0;                               // s
  std::array<int, 3> dir{0, 0, 0};              // sign of the last motion per axis
  std::string set;
  std::array<Eigen::Vector3d, 3> eps_urad{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                          Eigen::Vector3d::Zero()};  // ε_j of the base model
  Eigen::Vector3d model_delta_um = Eigen::Vector3d::Zero();  // other model − base model, µm
};

// The built-in kinds; effect_catalogue.hpp registers more (values ≥ 100).
enum class TermKind : int {
  model_choice,
  scale,
  squareness,
  reversal,
  thermal_drift,
  cyclic,
  coupling,
  arm_offset,
  setup_offset,
  setup_rotation,
  unexplained
};

// The catalogue id of DESIGN.md §5 ("setup" for both setup terms).
const char* kind_id(TermKind k);
// The overlay's `term:` name ("setup_offset", "setup_rotation", else the id).
const char* term_name(TermKind k);

struct Term {
  TermKind kind = TermKind::scale;
  int axis = -1;           // the axis whose position/motion drives it (setup_rotation: the rotation
                           // axis; arm_offset: the axis whose ε is used)
  int direction = -1;      // deviation direction (arm_offset: the direction of Δ); -1: several
  int with_axis = -1;      // coupling partner; thermal_drift: q_j·t when ≥ 0
  double period_mm = 0.0;  // cyclic
  double tau_s = 0.0;      // thermal_drift time constant (0: linear in t, per hour)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // coupling: travel mid; setup: rotation centre
  Eigen::Vector3d half = Eigen::Vector3d::Ones();    // coupling: travel half-range
  std::string set;                                   // setup terms
  std::string other_model;                           // model_choice
  // unexplained: Legendre products of the variables (0..2 = s_x, s_y, s_z, 3 = t)
  // scaled from [lo, hi] to [−1, 1], every degree combination up to `degree`
  // per variable except the constant.
  // (reversal: degree 1 is the reversal growing along its travel, about
  // `centre` in units of `half`.)
  std::vector<int> vars;  // kTimeVariable: the time
  int degree = 0;
  std::array<double, 4> lo{0, 0, 0, 0}, hi{1, 1, 1, 1};

  std::vector<double> coef;     // fitted coefficients (one per column)
  std::vector<double> stderr_;  // their standard errors
  // The standard uncertainty of the searched parameter (cyclic: period_mm;
  // thermal_drift with τ > 0: tau_s) from the final fit's curvature beside
  // the other named effects (final_fit.hpp); 0: not computed.
  double searched_stderr = 0.0;

  int columns() const;
  // g_c(point) for every column c, into out (3 × columns()).
  void basis(const PointContext& pc,
             Eigen::Ref<Eigen::Matrix<double, 3, Eigen::Dynamic>> out) const;
  // Σ coef_c g_c(point), µm.
  Eigen::Vector3d evaluate(const PointContext& pc) const;

  std::string label() const;        // e.g. "reversal Y→Y", "cyclic X→Z (16.0 mm)"
  std::string description() const;  // one plain-language line with the numbers
  // Named parameters (values, and their standard errors) for the report.
  // All of these go through the kind's descriptor (effect_catalogue.hpp).
  std::vector<std::pair<std::string, double>> params() const;
  std::vector<std::pair<std::string, double>> param_stderr() const;
};

// d_i ∝ s_a, the deviation in direction i linear in the position of axis
// a: the scale of a (i = a) or the squareness a→i.
Term position_term(int axis, int direction);

// The same effect (kind, axes, direction, set), perhaps in another form: a
// reversal with and without its growth, a drift at another time constant.
bool same_effect(const Term& a, const Term& b);

char axis_name(int a);             // 'X', 'Y', 'Z' ('-' for −1)
const char* variable_name(int v);  // "x", "y", "z", "t"

}  // namespace abbe::diagnose
