#include "abbe/diagnose/transfer.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "abbe/diagnose/candidates.hpp"
#include "abbe/diagnose/selection.hpp"
#include "span.hpp"

namespace abbe::diagnose {

namespace {

// The RMS (residual_stats) of y after the least-squares fit of the datum
// (which does not depend on the candidate options).
double rms_after_datum(const Problem& pb) {
  const Eigen::MatrixXd Q =
      span::orthonormal(span::columns_of(pb, build_candidates(pb, CandidateOptions{}).datum));
  return residual_stats(pb, span::residual_of(Q, pb.y)).rms_um;
}

}  // namespace

double TransferCheck::change_percent() const {
  return rms_without_um > 0.0 ? 100.0 * (1.0 - rms_with_um / rms_without_um) : 0.0;
}

TransferCheck check_transfer(const Problem& without, const Problem& with, std::size_t terms) {
  if (without.obs.size() != with.obs.size())
    throw std::invalid_argument("check_transfer: the two problems hold different observations");
  TransferCheck c;
  c.done = true;
  c.terms = terms;
  c.rms_without_um = rms_after_datum(without);
  c.rms_with_um = rms_after_datum(with);
  return c;
}

void add_overlay_warnings(const Overlay& overlay, const std::string& machine_name,
                          const std::string& model_name, const Problem& problem,
                          TransferCheck& check) {
  const std::string name = overlay.file.empty() ? "the overlay" : overlay.file;
  if (!overlay.machine.empty() && overlay.machine != machine_name)
    check.warnings.push_back(
        fmt::format("{} was fitted for machine \"{}\", these data are diagnosed against \"{}\"",
                    name, overlay.machine, machine_name));
  if (overlay.base_model != model_name)
    check.warnings.push_back(fmt::format("{} was fitted on the {} model, it is added to {}", name,
                                         overlay.base_model, model_name));
  check.points = problem.points.size();
  check.outside = 0;
  const bool with_time = overlay.time_dependent();
  for (const PointContext& pc : problem.points)
    check.outside += overlay.domain.contains(pc, with_time) ? 0 : 1;
  if (check.outside > 0)
    check.warnings.push_back(
        fmt::format("{} of the {} points lie outside the domain {} was fitted on ({}): its smooth, "
                    "polynomial and time terms are held at their boundary values there",
                    check.outside, check.points, name, overlay.domain.text(with_time)));
}

TransferCheck check_transfer(const machine::Machine& machine, const io::MeasuredData& data,
                             model::ModelKind model, const Overlay& overlay) {
  const Problem with = build_problem(machine, data, model, &overlay);
  TransferCheck c =
      check_transfer(build_problem(machine, data, model, nullptr), with, overlay.terms.size());
  add_overlay_warnings(overlay, machine.name(), model::to_string(model), with, c);
  return c;
}

}  // namespace abbe::diagnose
