#pragma once
// PredictionWriter: the per-point output of a prediction (`abbe predict`),
// CSV or JSON, formatted into a buffer handed to a byte sink in chunks.
//
// One model: CSV columns x,y,z,px,py,pz,dx,dy,dz,d[,dx2,dy2,dz2],line. Several
// models: x,y,z,line then px_<suffix>,…,d_<suffix> per model (the suffix is
// the model table's column_suffix; second-order models add dx2,dy2,dz2). JSON:
// {"points": [{"x":…, "line":…, "<model>": {"px":…}}, …], "summary": {…}}.
// Nominal and predicted points in mm, deviations in µm, 6 decimals.
// With `aligned` (abbe predict --align), each model's columns are followed by
// the deviation after the part's alignment: adx,ady,adz,ad (JSON: the same
// keys in the model's object).
// With `uncertainty` (abbe predict --uncertainty N), each model's columns end
// with the standard uncertainties u_dx,u_dy,u_dz (µm; JSON: the same keys).
// With both (--uncertainty N --align …), the uncertainties of the deviation
// after alignment follow: u_adx,u_ady,u_adz.
#include <fmt/format.h>

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "abbe/model/error_model.hpp"
#include "abbe/model/model_kind.hpp"
#include "abbe/pipeline/model_set.hpp"
#include "abbe/pipeline/path_writer.hpp"

namespace abbe::pipeline {

class PredictionWriter {
 public:
  PredictionWriter(PathFormat format, std::vector<model::ModelKind> kinds, ByteSink sink,
                   bool aligned = false, bool uncertainty = false);
  PredictionWriter(const PredictionWriter&) = delete;
  PredictionWriter& operator=(const PredictionWriter&) = delete;

  // One row: the point, its source line and the models' last evaluation.
  void write(const model::EvalPoint& point, std::size_t line, const ModelSet& models) {
    write_row(point, line, models.deviations(), models.norms_um());
  }
  // One row of an aligned prediction: per model the deviation, |e| and the
  // deviation after alignment (µm).
  void write(const model::EvalPoint& point, std::size_t line,
             const std::vector<model::Deviation>& devs, const std::vector<double>& norms_um,
             const std::vector<Eigen::Vector3d>& aligned_um);
  // One row of a prediction with uncertainty: per model the deviation, |e|
  // and the standard uncertainties of dx, dy, dz (µm).
  void write_uncertain(const model::EvalPoint& point, std::size_t line,
                       const std::vector<model::Deviation>& devs,
                       const std::vector<double>& norms_um,
                       const std::vector<Eigen::Vector3d>& u_um);
  // One row of an aligned prediction with uncertainty (both flags set).
  void write_uncertain(const model::EvalPoint& point, std::size_t line,
                       const std::vector<model::Deviation>& devs,
                       const std::vector<double>& norms_um,
                       const std::vector<Eigen::Vector3d>& aligned_um,
                       const std::vector<Eigen::Vector3d>& u_um,
                       const std::vector<Eigen::Vector3d>& u_aligned_um);
  // Writes the trailer (JSON: `summary_json` as the "summary" member) and
  // hands on what is buffered.
  void finish(std::string_view summary_json);
  std::size_t points() const { return points_; }

 private:
  // Formats one row through `out` and returns it advanced. By value: the
  // sink's pointer stays in a register (through a reference, every character
  // stored could alias it, so it would be stored and reloaded per number).
  template <class Out>
  Out row(Out out, const model::EvalPoint& p, const std::vector<model::Deviation>& devs,
          const std::vector<double>& norms) const;
  void write_row(const model::EvalPoint& p, std::size_t line,
                 const std::vector<model::Deviation>& devs, const std::vector<double>& norms);
  void put(std::string_view s) { buf_.append(s.data(), s.data() + s.size()); }
  void flush();

  PathFormat format_;
  std::vector<model::ModelKind> kinds_;
  std::vector<bool> second_order_;  // per model: writes dx2, dy2, dz2
  ByteSink sink_;
  std::vector<std::string> json_keys_;         // `, "<model>": {"px": ` per model
  std::size_t row_max_ = 192;                  // bytes an in-place row may take
  std::vector<Eigen::Vector3d> pred_;          // predicted tool tip per model, mm
  bool aligned_ = false;                       // adx,ady,adz,ad columns
  std::vector<Eigen::Vector3d> aligned_um_;    // of the row being written
  bool uncertain_ = false;                     // u_dx,u_dy,u_dz columns
  std::vector<Eigen::Vector3d> u_um_;          // of the row being written
  std::vector<Eigen::Vector3d> u_aligned_um_;  // u_adx,u_ady,u_adz: both flags
  fmt::memory_buffer buf_;
  std::size_t points_ = 0;
  std::array<char, 24> line_text_{};
  std::size_t line_size_ = 0;
  std::size_t line_ = 0;
};

}  // namespace abbe::pipeline
