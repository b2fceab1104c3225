#pragma once
// What an overlay fitted on other data does on these data (docs/diagnosis.md,
// "Transfer"): the residual after the datum — refitted here, a new
// measurement has its own — without and with the overlay's terms. `abbe
// diagnose --extend OVERLAY` reports it, so one plate's model can be
// checked on another plate.
#include <cstddef>
#include <string>
#include <vector>

#include "abbe/diagnose/overlay.hpp"
#include "abbe/diagnose/residuals.hpp"
#include "abbe/io/measured_data.hpp"
#include "abbe/machine/machine.hpp"
#include "abbe/model/model_kind.hpp"

namespace abbe::diagnose {

struct TransferCheck {
  bool done = false;
  std::size_t terms = 0;        // the overlay's terms
  double rms_without_um = 0.0;  // after the datum: the model alone
  double rms_with_um = 0.0;     // after the datum: the model and the overlay
  std::size_t points = 0;       // the points checked
  std::size_t outside = 0;      // of them outside the overlay's domain (box, time window)
  // What the user should know before trusting the numbers: the overlay was
  // fitted for another machine or on another model, or points lie outside
  // its domain (its smooth and time terms are held there).
  std::vector<std::string> warnings;
  // + when the overlay lowers the RMS: 100·(1 − with/without).
  double change_percent() const;
};

// The warnings of a TransferCheck for an overlay applied to these points,
// diagnosed against `machine_name` with `model_name`; fills `points` and
// `outside` of `check` too.
void add_overlay_warnings(const Overlay& overlay, const std::string& machine_name,
                          const std::string& model_name, const Problem& problem,
                          TransferCheck& check);

// `without` and `with`: the same points, the model's residual without and
// with the overlay (build_problem with extend = nullptr and = &overlay).
TransferCheck check_transfer(const Problem& without, const Problem& with, std::size_t terms);

TransferCheck check_transfer(const machine::Machine& machine, const io::MeasuredData& data,
                             model::ModelKind model, const Overlay& overlay);

}  // namespace abbe::diagnose
