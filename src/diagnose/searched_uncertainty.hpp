#pragma once
// The standard uncertainty of a fitted effect's searched parameter (a
// cycle's period, a drift's time constant), which the linear fit does not
// give: the Gauss–Newton linearisation of the term in that parameter.
#include "abbe/diagnose/residuals.hpp"
#include "abbe/diagnose/term.hpp"
#include "candidate_fit.hpp"

namespace abbe::diagnose::selection {

// ∂(C(θ)β)/∂θ per observation (central difference) of a fitted term with a
// searched parameter (a cycle's period, a drift's τ); empty for a term
// without one.
Vec searched_derivative(const Problem& pb, const Term& fitted);

// u(θ) = σ̂ / ‖(I − X (XᵀX)⁻¹ Xᵀ) ∂(C(θ)β)/∂θ‖: the derivative of the
// fitted term's contribution in θ (central difference), less what the
// fit's other columns X (the term's own among them) take of it, gives θ's
// variance σ̂² / ‖·‖² (the (θ, θ) element of the inverse of the augmented
// normal matrix). `fitted` carries its coefficients; XtX_inv is (XᵀX)⁻¹;
// s2 = σ̂². Returns 0 for a term without a searched parameter (a drift
// linear in t has none), +∞ when the data do not fix it at all.
double searched_parameter_stderr(const Problem& pb, const Term& fitted, const Mat& X,
                                 const Mat& XtX_inv, double s2);

}  // namespace abbe::diagnose::selection
