#include "abbe/diagnose/transfer.hpp"

#include <stdexcept>

#include "abbe/diagnose/selection.hpp"
#include "span.hpp"

namespace abbe::diagnose {

namespace {

// The RMS (residual_stats) of y after the least-squares fit of the datum.
double rms_after_datum(const Problem& pb, const CandidateOptions& options) {
  const std::vector<Term> datum = build_candidates(pb, options).datum;
  Eigen::MatrixXd D(static_cast<Eigen::Index>(pb.obs.size()), 0);
  for (const Term& t : datum) {
    const Eigen::MatrixXd c = term_columns(pb, t);
    D.conservativeResize(Eigen::NoChange, D.cols() + c.cols());
    D.rightCols(c.cols()) = c;
  }
  const Eigen::MatrixXd Q = span::orthonormal(D);
  return residual_stats(pb, span::residual_of(Q, pb.y)).rms_um;
}

}  // namespace

double TransferCheck::change_percent() const {
  return rms_without_um > 0.0 ? 100.0 * (1.0 - rms_with_um / rms_without_um) : 0.0;
}

TransferCheck check_transfer(const Problem& without, const Problem& with, std::size_t terms,
                             const CandidateOptions& options) {
  if (without.obs.size() != with.obs.size())
    throw std::invalid_argument("check_transfer: the two problems hold different observations");
  TransferCheck c;
  c.done = true;
  c.terms = terms;
  c.rms_without_um = rms_after_datum(without, options);
  c.rms_with_um = rms_after_datum(with, options);
  return c;
}

TransferCheck check_transfer(const machine::Machine& machine, const io::MeasuredData& data,
                             model::ModelKind model, const Overlay& overlay,
                             const CandidateOptions& options) {
  return check_transfer(build_problem(machine, data, model, nullptr),
                        build_problem(machine, data, model, &overlay), overlay.terms.size(),
                        options);
}

}  // namespace abbe::diagnose
