#pragma once
// The diagnose report: the residual of the diagnosed model (measured −
// predicted, µm, per observation along its measured direction) against each
// variable — axis positions s_x, s_y, s_z and time t — before and after the
// extension by the selected effects, the model comparison and the effect
// table (kind, axis, share of the residual explained, description).
#include "abbe/diagnose/diagnosis.hpp"
#include "abbe/diagnose/residuals.hpp"
#include "abbe/report/html_page.hpp"

namespace abbe::report {

struct DiagnosisForReport {
  diagnose::Diagnosis diagnosis;
  diagnose::Problem before;  // residual of the model
  diagnose::Problem after;   // residual of the model + the selected effects (overlay) + datum
};

// Runs the diagnosis, then rebuilds the residual with its overlay added.
DiagnosisForReport diagnose_for_report(const machine::Machine& machine,
                                       const io::MeasuredData& data,
                                       const diagnose::DiagnoseOptions& options);

void render_diagnose_report(HtmlPage& page, const DiagnosisForReport& d);

}  // namespace abbe::report
